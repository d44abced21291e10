#pragma once
// What bmp-mapper's receive thread hands its loop: keyframes and pose updates in the order they came, held
// up to a budget in bytes. The loop takes seconds now and then (a burst of keyframes, stitching and carving
// a map of a million points, saving it). Read from the loop itself, messages waited in LCM's own queue,
// which holds 30 a subscription and drops the rest without a word: of 60 keyframes sent every 20 ms, 45 were
// mapped and the heartbeat counted none dropped. Here what does not fit is dropped and counted. Bytes, not
// messages: forged 16-megapixel keyframes (80 MB each, within the camera bounds) must not fill memory.
#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <utility>
#include <variant>

#include <bmp/keyframe_poses_t.hpp>
#include <bmp/keyframe_t.hpp>

#include "bmp/common/bounded_queue.hpp"

namespace bmp::mapper {

class MapperInbox {
 public:
  using Message = std::variant<keyframe_t, keyframe_poses_t>;

  explicit MapperInbox(std::size_t max_bytes);

  // On the receive thread. False, and the message counted as refused, when the messages waiting already
  // hold max_bytes with it; a message always fits an empty inbox (LCM's own checks bound its size).
  bool offer(Message message);
  // On the loop's thread.
  std::optional<Message> popFor(std::chrono::milliseconds timeout);
  std::optional<Message> tryPop();
  void close();  // later offers are refused; what waits can still be taken

  int64_t refusedCount() const { return refused_.load(); }
  std::size_t waitingBytes() const { return bytes_.load(); }

  static std::size_t bytesOf(const Message& message);

 private:
  std::optional<Message> taken(std::optional<std::pair<Message, std::size_t>> item);

  const std::size_t max_bytes_;
  BoundedQueue<std::pair<Message, std::size_t>> queue_;
  std::atomic<std::size_t> bytes_{0};
  std::atomic<int64_t> refused_{0};
};

}  // namespace bmp::mapper

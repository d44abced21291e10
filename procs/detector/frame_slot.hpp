#pragma once
// The hand-over between the thread that receives frames and the inference thread. In "latest" mode a new
// frame replaces the one still waiting (newest wins, the replaced one is counted as dropped), so a slow
// detector always works on the freshest image. In "every" mode frames queue up to a fixed capacity and
// the producer waits when it is full, so lockstep runs process every frame.
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <mutex>
#include <optional>
#include <string>

namespace bmp::detector {

enum class QueueMode { kLatest, kEvery };

// Throws std::invalid_argument for anything but "latest" or "every".
QueueMode parseQueueMode(const std::string& text);
const char* toString(QueueMode mode);

template <typename T>
class FrameSlot {
 public:
  // capacity: frames held in "every" mode (at least 1); "latest" mode holds one.
  FrameSlot(QueueMode mode, std::size_t capacity)
      : mode_(mode), capacity_(mode == QueueMode::kLatest ? 1 : (capacity > 0 ? capacity : 1)) {}

  // Returns how many waiting frames this one displaced (0 or 1; always 0 in "every" mode). After close()
  // the item is discarded and counts as dropped.
  std::size_t push(T item) {
    std::unique_lock<std::mutex> lock(mutex_);
    if (mode_ == QueueMode::kEvery) {
      space_.wait(lock, [&] { return closed_ || items_.size() < capacity_; });
    }
    if (closed_) return 1;
    std::size_t dropped = 0;
    if (mode_ == QueueMode::kLatest && !items_.empty()) {
      items_.clear();
      dropped = 1;
    }
    items_.push_back(std::move(item));
    ready_.notify_one();
    return dropped;
  }

  // Waits for a frame; empty once closed and drained.
  std::optional<T> pop() {
    std::unique_lock<std::mutex> lock(mutex_);
    ready_.wait(lock, [&] { return closed_ || !items_.empty(); });
    if (items_.empty()) return std::nullopt;
    T item = std::move(items_.front());
    items_.pop_front();
    space_.notify_one();
    return item;
  }

  // Wakes every waiter; pop() still hands out what is queued.
  void close() {
    std::lock_guard<std::mutex> lock(mutex_);
    closed_ = true;
    ready_.notify_all();
    space_.notify_all();
  }

  std::size_t size() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return items_.size();
  }
  QueueMode mode() const { return mode_; }

 private:
  const QueueMode mode_;
  const std::size_t capacity_;
  mutable std::mutex mutex_;
  std::condition_variable ready_;
  std::condition_variable space_;
  std::deque<T> items_;
  bool closed_ = false;
};

}  // namespace bmp::detector

#pragma once
// The last answer a consumer published for a frame (a slam_pose_t or detections_t: both carry the frame's
// seq and utime), kept to be published again when lockstep capture resends that frame because its answer
// is late: the frame or the answer may have been lost on the way. Thread-safe: the tracker answers on its
// processing thread and hears the repeat on its receive thread.
#include <atomic>
#include <cstdint>
#include <mutex>
#include <optional>
#include <string>

#include "bmp/lcm/lcm_node.hpp"

namespace bmp {

template <typename Answer>
class LastAnswer {
 public:
  void remember(const Answer& answer) {
    const std::lock_guard<std::mutex> lock(mutex_);
    last_ = answer;
  }
  // The answer given to frame (seq, utime), or nullopt when the last answer was for another frame (this
  // one is still being worked on, or was never received).
  std::optional<Answer> forFrame(int64_t seq, int64_t utime) const {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (last_ && last_->seq == seq && last_->utime == utime) return last_;
    return std::nullopt;
  }
  // For a repeated frame: publishes its answer again on channel if it is out (else the pending one will go
  // out) and counts it.
  void answerRepeat(LcmNode& lcm, const std::string& channel, int64_t seq, int64_t utime) {
    if (const auto again = forFrame(seq, utime)) {
      lcm.publish(channel, *again);
      ++answered_again_;
    }
  }
  int64_t answeredAgain() const { return answered_again_.load(); }

 private:
  std::atomic<int64_t> answered_again_{0};
  mutable std::mutex mutex_;
  std::optional<Answer> last_;
};

}  // namespace bmp

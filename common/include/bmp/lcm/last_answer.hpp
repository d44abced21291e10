#pragma once
// The last answer a consumer published for a frame (a slam_pose_t or detections_t: both carry the frame's
// seq and utime), kept to be published again when lockstep capture resends that frame because its answer
// is late: the frame or the answer may have been lost on the way. Thread-safe: the tracker answers on its
// processing thread and hears the repeat on its receive thread.
#include <cstdint>
#include <mutex>
#include <optional>

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

 private:
  mutable std::mutex mutex_;
  std::optional<Answer> last_;
};

}  // namespace bmp

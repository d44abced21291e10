#include "capture/looped_source.hpp"

#include <stdexcept>

namespace bmp::capture {

double loopPeriod(double first_stamp, double last_stamp, int64_t frames) {
  if (frames < 2 || last_stamp <= first_stamp) return 1.0;
  const double duration = last_stamp - first_stamp;
  return duration + duration / static_cast<double>(frames - 1);
}

LoopedSource::LoopedSource(std::unique_ptr<FrameSource> first, Opener open, int loops, double period_s)
    : current_(std::move(first)), open_(std::move(open)), loops_(loops), period_s_(period_s) {
  if (loops_ < 1) throw std::invalid_argument("loop: must play at least once");
  per_pass_ = current_->size();
}

std::optional<CapturedFrame> LoopedSource::next() {
  while (true) {
    std::optional<CapturedFrame> frame = current_->next();
    if (frame) {
      if (pass_ == 0) {
        if (first_pass_frames_++ == 0) first_stamp_ = frame->stamp;
        last_stamp_ = frame->stamp;
        return frame;
      }
      const double offset = period_s_ * pass_;
      frame->stamp += offset;
      frame->depth_stamp += offset;
      frame->index += per_pass_ * pass_;
      return frame;
    }
    if (pass_ + 1 >= loops_ || first_pass_frames_ == 0) return std::nullopt;
    if (pass_ == 0 && period_s_ <= 0) period_s_ = loopPeriod(first_stamp_, last_stamp_, first_pass_frames_);
    const SkipReport& done = current_->skips();
    earlier_.missing_files += done.missing_files;
    earlier_.corrupt_files += done.corrupt_files;
    earlier_.wrong_size += done.wrong_size;
    if (!done.last_reason.empty()) earlier_.last_reason = done.last_reason;
    current_ = open_();
    ++pass_;
  }
}

const SkipReport& LoopedSource::skips() const {
  const SkipReport& now = current_->skips();
  total_ = earlier_;
  total_.missing_files += now.missing_files;
  total_.corrupt_files += now.corrupt_files;
  total_.wrong_size += now.wrong_size;
  if (!now.last_reason.empty()) total_.last_reason = now.last_reason;
  return total_;
}

}  // namespace bmp::capture

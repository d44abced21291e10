#pragma once
// --loop N: plays a source N times as one stream that only moves forward, for long (soak) runs from a short
// sequence. Each pass's stamps are offset by the sequence's period (its duration plus one frame interval)
// times the pass number, and frame indices continue, so a consumer sees one recording N times as long and
// its checks (stamps and seq that move forward) hold; the camera jumps back to the start at each seam, as a
// robot revisiting its room would.
#include <functional>
#include <memory>

#include "capture/frame_source.hpp"

namespace bmp::capture {

class LoopedSource : public FrameSource {
 public:
  using Opener = std::function<std::unique_ptr<FrameSource>()>;
  // first: the first pass (already open); open: a fresh source for each later pass. period_s <= 0: measured
  // from the first pass's stamps.
  LoopedSource(std::unique_ptr<FrameSource> first, Opener open, int loops, double period_s = 0.0);
  std::optional<CapturedFrame> next() override;
  const CameraIntrinsics& camera() const override { return current_->camera(); }
  std::string name() const override { return current_->name(); }
  int64_t size() const override { return per_pass_ * loops_; }
  const SkipReport& skips() const override;

 private:
  std::unique_ptr<FrameSource> current_;
  Opener open_;
  int loops_;
  int pass_ = 0;
  int64_t per_pass_;
  double period_s_;
  double first_stamp_ = 0.0, last_stamp_ = 0.0;
  int64_t first_pass_frames_ = 0;
  SkipReport earlier_;  // the finished passes' skips
  mutable SkipReport total_;
};

// The period of a pass whose first and last frame stamps and frame count are given: duration plus one mean
// frame interval (1 s for a single frame).
double loopPeriod(double first_stamp, double last_stamp, int64_t frames);

}  // namespace bmp::capture

// --loop: N passes over a source look like one recording N times as long: stamps and indices only move
// forward, each pass offset by the sequence's period, and skips add up over the passes.
#include <gtest/gtest.h>

#include "capture/looped_source.hpp"

namespace bmp::capture {
namespace {

// Three frames 0.1 s apart, starting at 100 s; one skipped file per pass.
class ThreeFrames : public FrameSource {
 public:
  ThreeFrames() { skips_.missing_files = 1; }
  std::optional<CapturedFrame> next() override {
    if (i_ == 3) return std::nullopt;
    CapturedFrame f;
    f.index = i_;
    f.stamp = 100.0 + 0.1 * static_cast<double>(i_);
    f.depth_stamp = f.stamp + 0.01;
    ++i_;
    return f;
  }
  const CameraIntrinsics& camera() const override { return camera_; }
  std::string name() const override { return "three"; }
  int64_t size() const override { return 3; }
  const SkipReport& skips() const override { return skips_; }

 private:
  int64_t i_ = 0;
  CameraIntrinsics camera_;
  SkipReport skips_;
};

TEST(LoopedSource, PassesFormOneForwardStream) {
  LoopedSource looped(
      std::make_unique<ThreeFrames>(), [] { return std::make_unique<ThreeFrames>(); }, 3);
  EXPECT_EQ(looped.size(), 9);
  std::vector<CapturedFrame> frames;
  while (auto f = looped.next()) frames.push_back(*f);
  ASSERT_EQ(frames.size(), 9u);
  for (std::size_t i = 0; i < frames.size(); ++i) {
    EXPECT_EQ(frames[i].index, static_cast<int64_t>(i));
    // Period: 0.2 s of duration plus one 0.1 s interval, so the stream keeps its 10 Hz across the seam.
    EXPECT_NEAR(frames[i].stamp, 100.0 + 0.1 * static_cast<double>(i), 1e-9) << i;
    EXPECT_NEAR(frames[i].depth_stamp - frames[i].stamp, 0.01, 1e-9);
  }
  EXPECT_EQ(looped.skips().missing_files, 3);
}

TEST(LoopedSource, GivenPeriodAndOnePass) {
  LoopedSource given(
      std::make_unique<ThreeFrames>(), [] { return std::make_unique<ThreeFrames>(); }, 2, 5.0);
  std::vector<double> stamps;
  while (auto f = given.next()) stamps.push_back(f->stamp);
  ASSERT_EQ(stamps.size(), 6u);
  EXPECT_NEAR(stamps[3], 105.0, 1e-9);
  LoopedSource once(
      std::make_unique<ThreeFrames>(), [] { return std::make_unique<ThreeFrames>(); }, 1);
  int n = 0;
  while (once.next()) ++n;
  EXPECT_EQ(n, 3);
  EXPECT_NEAR(loopPeriod(0.0, 0.0, 1), 1.0, 1e-12);
}

}  // namespace
}  // namespace bmp::capture

// The tracker on bmp-capture's synthetic room: static (ATE against exact ground truth) and with frames
// withheld (relocalisation).
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>

#include "capture/synthetic_scene.hpp"
#include "eval/ate.hpp"
#include "tracker_offline/offline_runner.hpp"

namespace bmp::tracker {
namespace {

capture::SyntheticSceneConfig staticScene(int frames) {
  capture::SyntheticSceneConfig config;  // the defaults of config/synthetic.yaml
  config.num_frames = frames;
  config.num_moving_objects = 0;
  return config;
}

FrameProvider sceneFrames(std::shared_ptr<const capture::SyntheticScene> scene) {
  auto next = std::make_shared<int>(0);
  return [scene, next]() -> std::optional<OfflineFrame> {
    if (*next >= scene->numFrames()) return std::nullopt;
    const capture::SyntheticFrame f = scene->render((*next)++);
    return OfflineFrame{f.stamp, f.bgr, f.depth, cv::Mat(), std::nullopt, std::nullopt};
  };
}

TEST(TrackerSynthetic, StaticSceneAteBelow5mm) {
  auto scene = std::make_shared<const capture::SyntheticScene>(staticScene(240));
  TrackerConfig config;
  config.mapping.threaded = false;  // deterministic
  Tracker tracker(scene->camera(), config);
  const OfflineResult result = runOffline(tracker, sceneFrames(scene));
  ASSERT_EQ(result.frames, 240);
  EXPECT_EQ(result.frames_lost, 0);
  EXPECT_EQ(result.trajectory.size(), 240u);
  const eval::ErrorStats ate = eval::computeAte(scene->groundTruth(), result.trajectory).stats;
  EXPECT_LT(ate.rmse, 0.005) << "ATE RMSE " << ate.rmse;
  std::printf("synthetic static: ATE RMSE %.4f m, max %.4f m, %zu keyframes, median %.1f ms\n", ate.rmse,
              ate.max, result.keyframe_trajectory.size(), result.track_ms.median());
}

TrackerInput inputOf(const capture::SyntheticFrame& f, int64_t seq) {
  TrackerInput in;
  in.stamp = f.stamp;
  in.seq = seq;
  in.image = f.bgr;
  in.depth = f.depth;
  return in;
}

// Track 90 frames, cover the camera for 5 (black, no depth: lost), withhold 30, then resume: the tracker
// must relocalise against its keyframes, continue OK, and place the camera where the ground truth says.
TEST(TrackerSynthetic, RelocalisesAfterFramesAreWithheld) {
  auto scene = std::make_shared<const capture::SyntheticScene>(staticScene(170));
  TrackerConfig config;
  config.mapping.threaded = false;
  Tracker tracker(scene->camera(), config);
  int64_t seq = 0;
  for (int i = 0; i < 90; ++i)
    ASSERT_TRUE(tracker.track(inputOf(scene->render(i), seq++)).ok()) << "frame " << i;
  const capture::SyntheticFrame probe = scene->render(90);
  for (int i = 0; i < 5; ++i) {
    capture::SyntheticFrame dark = probe;
    dark.bgr = cv::Mat::zeros(probe.bgr.size(), probe.bgr.type());
    dark.depth = cv::Mat::zeros(probe.depth.size(), probe.depth.type());
    dark.stamp = probe.stamp + 0.001 * i;
    EXPECT_EQ(tracker.track(inputOf(dark, seq++)).state, TrackingState::kLost);
  }
  tracker.forgetMotion();
  std::vector<TrackResult> after;
  for (int i = 125; i < 170; ++i) after.push_back(tracker.track(inputOf(scene->render(i), seq++)));
  ASSERT_EQ(after.front().state, TrackingState::kRelocalised) << toString(after.front().state);
  for (std::size_t k = 1; k < after.size(); ++k)
    EXPECT_EQ(after[k].state, TrackingState::kOk) << "frame " << 125 + k;

  // The map frame is the first camera's; compare relative to frame 0 of the ground truth.
  const SE3 T_gt_map = scene->cameraPose(0);
  double worst = 0.0;
  for (std::size_t k = 0; k < after.size(); ++k) {
    const SE3 expected = T_gt_map.inverse() * scene->cameraPose(125 + static_cast<int>(k));
    worst = std::max(worst, (expected.translation() - after[k].T_world_cam.translation()).norm());
  }
  EXPECT_LT(worst, 0.02) << "worst position error after relocalisation " << worst;
}

}  // namespace
}  // namespace bmp::tracker

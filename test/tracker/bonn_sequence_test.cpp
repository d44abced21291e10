// The tracker on the first frames of the real Bonn crowd sequence (few people in view yet).
#include <gtest/gtest.h>

#include "bmp/common/camera_config.hpp"
#include "bmp/common/config.hpp"
#include "eval/ate.hpp"
#include "shared_data.hpp"
#include "tracker_offline/offline_runner.hpp"

namespace bmp::tracker {
namespace {

CameraIntrinsics bonnCamera() {
  const Config file = Config::fromFile(test::sourceDir() + "/config/cameras/bonn.yaml");
  return cameraFromConfig(file.section("camera"));
}

TEST(TrackerBonn, First150FramesTrackWithSmallError) {
  TrackerConfig config;
  config.mapping.threaded = false;  // deterministic
  Tracker tracker(bonnCamera(), config);
  Trajectory groundtruth;
  OfflineOptions options;
  options.max_frames = 150;
  const OfflineResult result =
      runOffline(tracker, tumFolderFrames(test::bonnDir(), 0, &groundtruth), options);
  ASSERT_EQ(result.frames, 150);
  EXPECT_EQ(result.frames_lost, 0);
  EXPECT_FALSE(result.lost_at_end);
  EXPECT_GE(result.trajectory.size(), 148u);
  EXPECT_GE(result.keyframe_trajectory.size(), 2u);
  const double rmse = eval::computeAte(groundtruth, result.trajectory).stats.rmse;
  // Measured 1.2 cm on this stretch; 3 cm leaves room for platform differences while still failing on any
  // real regression (losing the static world to a passing person costs tens of centimetres).
  EXPECT_LT(rmse, 0.03) << "ATE RMSE " << rmse;
}

// The whole sequence, people walking close to the camera throughout, with no dynamic handling.
TEST(TrackerBonn, WholeSequenceNoWorseThanOrbSlam2) {
  TrackerConfig config;
  config.mapping.threaded = false;
  Tracker tracker(bonnCamera(), config);
  Trajectory groundtruth;
  const OfflineResult result = runOffline(tracker, tumFolderFrames(test::bonnDir(), 0, &groundtruth));
  ASSERT_GT(result.frames, 900);
  EXPECT_FALSE(result.lost_at_end);
  EXPECT_LE(result.frames_lost, 10);
  const double rmse = eval::computeAte(groundtruth, result.trajectory).stats.rmse;
  std::printf("bonn crowd: %d frames, %d lost, ATE RMSE %.4f m, tracking median %.1f ms\n", result.frames,
              result.frames_lost, rmse, result.track_ms.median());
  // ORB-SLAM2 reaches 4.9 cm here (WildGS-SLAM paper, table 3): the bar for a static-world SLAM.
  EXPECT_LT(rmse, 0.049) << "ATE RMSE " << rmse;
}

}  // namespace
}  // namespace bmp::tracker

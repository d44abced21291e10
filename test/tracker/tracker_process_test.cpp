// The real bmp-tracker over LCM: Bonn frames in (lockstep), one SLAM_POSE per frame (a damaged one answered
// as skipped), keyframes with decodable images, the TUM trajectories written on SIGINT, and kept on SIGKILL.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <bmp/keyframe_t.hpp>
#include <bmp/process_status_t.hpp>
#include <bmp/rgbd_frame_t.hpp>
#include <bmp/slam_pose_t.hpp>

#include "bmp/common/child_process.hpp"
#include "bmp/common/image_codec.hpp"
#include "bmp/common/tum_trajectory.hpp"
#include "bmp/lcm/conversions.hpp"
#include "bmp/lcm/lcm_node.hpp"
#include "capture/tum_sequence.hpp"
#include "file_image.hpp"
#include "lcm_url.hpp"
#include "shared_data.hpp"

namespace bmp {
namespace {

camera_t bonnCamera() {
  camera_t c;
  c.width = 640;
  c.height = 480;
  c.fx = 542.822841;
  c.fy = 542.576870;
  c.cx = 315.593520;
  c.cy = 237.756098;
  const double d[5] = {0.039903, -0.099343, -0.000730, -0.000144, 0.0};
  for (int i = 0; i < 5; ++i) c.distortion[i] = d[i];
  return c;
}

// A bmp-tracker child on a test-unique udpm URL, and the test's own LCM node that feeds and watches it.
class TrackerUnderTest {
 public:
  explicit TrackerUnderTest(const std::string& name, int slot)
      : url_(test::uniqueLcmUrl(slot)),
        dir_(test::scratchDir(name)),
        node_(url_),
        index_(capture::indexSequence(test::bonnDir())) {
    node_.subscribe<slam_pose_t>("SLAM_POSE",
                                 [this](const slam_pose_t& m, const ReceivedInfo&) { poses.push_back(m); });
    node_.subscribe<keyframe_t>("SLAM_KEYFRAME",
                                [this](const keyframe_t& m, const ReceivedInfo&) { keyframes.push_back(m); });
    node_.subscribe<process_status_t>("PROCESS_STATUS",
                                      [this](const process_status_t& m, const ReceivedInfo&) {
                                        heartbeat_ = heartbeat_ || m.name == "bmp-tracker";
                                      });
    child_ = std::make_unique<ChildProcess>(
        std::vector<std::string>{test::binPath("bmp-tracker"), "--config",
                                 test::sourceDir() + "/config/tracker.yaml", "--lcm-url", url_,
                                 "--trajectory", trajectory(), "--keyframe-trajectory", keyframeTrajectory()},
        ChildProcess::Output::kFile, logPath());
  }

  std::string trajectory() const { return (dir_ / "trajectory.txt").string(); }
  std::string keyframeTrajectory() const { return (dir_ / "keyframes.txt").string(); }
  std::string logPath() const { return (dir_ / "bmp-tracker.log").string(); }
  ChildProcess& child() { return *child_; }

  bool pumpUntil(const std::function<bool()>& done, double timeout_s) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
    while (!done() && std::chrono::steady_clock::now() < end) node_.handle(20);
    return done();
  }
  bool ready() {
    return pumpUntil([&] { return heartbeat_ || !child_->running(); }, 30.0) && child_->running();
  }

  // Publishes Bonn frame i and waits for its pose, as bmp-capture's lockstep does.
  // damage: replaces the depth with bytes that are no PNG, as another publisher might send.
  bool playAndWait(int i, bool damage = false) {
    const auto& pair = index_.frames[i];
    rgbd_frame_t msg;
    msg.seq = i;
    msg.utime = static_cast<int64_t>(pair.rgb_stamp * 1e6 + 0.5);
    msg.depth_utime = static_cast<int64_t>(pair.depth_stamp * 1e6 + 0.5);
    msg.source = "rgbd_bonn_crowd";
    msg.camera = bonnCamera();
    msg.depth_scale = 5000.0;
    msg.color = test::fileImage(pair.rgb_path, PixelFormat::kBgr8);
    msg.depth = test::fileImage(pair.depth_path, PixelFormat::kMono16);
    if (damage) msg.depth.data.assign(msg.depth.data.size(), 0x5a);
    node_.publish("RGBD_FRAME", msg);
    return pumpUntil([&] { return static_cast<int>(poses.size()) > i; }, 20.0);
  }

  std::vector<slam_pose_t> poses;
  std::vector<keyframe_t> keyframes;

 private:
  std::string url_;
  std::filesystem::path dir_;
  LcmNode node_;
  capture::SequenceIndex index_;
  bool heartbeat_ = false;
  std::unique_ptr<ChildProcess> child_;
};

TEST(TrackerProcess, PosePerFrameKeyframesAndTrajectoryOnSigint) {
  TrackerUnderTest t("tracker_process", 0);
  ASSERT_TRUE(t.ready()) << "no heartbeat, or it exited; log " << t.logPath();
  const int n = 40;
  const int damaged = 20;  // undecodable depth: answered as skipped, tracking goes on
  for (int i = 0; i < n; ++i) ASSERT_TRUE(t.playAndWait(i, i == damaged)) << "no pose for " << i;
  const std::vector<slam_pose_t>& poses = t.poses;
  const std::vector<keyframe_t>& kfs = t.keyframes;
  ASSERT_EQ(poses.size(), static_cast<std::size_t>(n));
  EXPECT_EQ(poses[damaged].seq, damaged);
  EXPECT_EQ(static_cast<int>(poses[damaged].state), static_cast<int>(slam_pose_t::STATE_SKIPPED));
  for (int i = 0; i < n; ++i) {
    EXPECT_EQ(poses[i].seq, i);
    if (i == damaged) continue;
    EXPECT_EQ(static_cast<int>(poses[i].state), static_cast<int>(slam_pose_t::STATE_OK)) << "frame " << i;
    EXPECT_EQ(poses[i].num_keypoints, 1000);
    EXPECT_GT(poses[i].processing_ms, 0.0f);
    if (i > 0) {
      EXPECT_GT(poses[i].num_tracked, 100) << "frame " << i;
    }
  }
  ASSERT_GE(kfs.size(), 1u);
  EXPECT_EQ(kfs[0].id, 0);
  EXPECT_EQ(kfs[0].seq, 0);
  const cv::Mat color = decodeImage(fromMsg(kfs[0].color));
  const cv::Mat depth = decodeImage(fromMsg(kfs[0].depth));
  const cv::Mat mask = decodeImage(fromMsg(kfs[0].dynamic_mask));
  EXPECT_EQ(color.type(), CV_8UC3);
  EXPECT_EQ(depth.type(), CV_16UC1);
  EXPECT_EQ(mask.type(), CV_8UC1);
  EXPECT_EQ(cv::countNonZero(mask), 0);

  EXPECT_EQ(t.child().stop(20.0), 0) << "log " << t.logPath();
  const Trajectory written = readTumTrajectory(t.trajectory());
  EXPECT_EQ(written.size(), static_cast<std::size_t>(n - 1));  // every frame but the skipped one
  EXPECT_GE(readTumTrajectory(t.keyframeTrajectory()).size(), 1u);
  // The clean exit replaced the live file with the optimised trajectory.
  EXPECT_EQ(test::readFirstLine(t.trajectory()), "# timestamp tx ty tz qx qy qz qw");
}

// Killed without a chance to write (SIGKILL), the tracker still leaves every pose it had published.
TEST(TrackerProcess, KilledTrackerLeavesThePosesItPublished) {
  TrackerUnderTest t("tracker_killed", 1);
  ASSERT_TRUE(t.ready()) << "no heartbeat, or it exited; log " << t.logPath();
  const int n = 15;
  for (int i = 0; i < n; ++i) ASSERT_TRUE(t.playAndWait(i)) << "no pose for " << i;
  t.child().signal(SIGKILL);
  ASSERT_TRUE(t.child().wait(10).has_value());
  const Trajectory live = readTumTrajectory(t.trajectory());
  ASSERT_EQ(live.size(), static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    EXPECT_NEAR(live[i].stamp, t.poses[i].utime * 1e-6, 1e-6);
    EXPECT_LT((live[i].T_world_cam.translation() - fromMsg(t.poses[i].T_world_cam).translation()).norm(),
              1e-6);
  }
  EXPECT_NE(test::readFirstLine(t.trajectory()).find("live poses"), std::string::npos);
  EXPECT_GE(readTumTrajectory(t.keyframeTrajectory()).size(), 1u);
}

}  // namespace
}  // namespace bmp

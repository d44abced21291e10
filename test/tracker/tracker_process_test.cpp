// The real bmp-tracker over LCM: Bonn frames in (lockstep), one SLAM_POSE per frame, keyframes with decodable
// images, and the TUM trajectories written on SIGINT.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
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

TEST(TrackerProcess, PosePerFrameKeyframesAndTrajectoryOnSigint) {
  const int port = 23000 + static_cast<int>(getpid() % 20000);
  const std::string url = "udpm://239.255.76.67:" + std::to_string(port) + "?ttl=0&recv_buf_size=4194304";
  const auto dir = test::scratchDir("tracker_process");
  const std::string trajectory = (dir / "trajectory.txt").string();
  const std::string keyframes = (dir / "keyframes.txt").string();
  const std::string log_path = (dir / "bmp-tracker.log").string();

  LcmNode node(url);
  std::vector<slam_pose_t> poses;
  std::vector<keyframe_t> kfs;
  bool heartbeat = false;
  node.subscribe<slam_pose_t>("SLAM_POSE",
                              [&](const slam_pose_t& m, const ReceivedInfo&) { poses.push_back(m); });
  node.subscribe<keyframe_t>("SLAM_KEYFRAME",
                             [&](const keyframe_t& m, const ReceivedInfo&) { kfs.push_back(m); });
  node.subscribe<process_status_t>("PROCESS_STATUS", [&](const process_status_t& m, const ReceivedInfo&) {
    heartbeat = heartbeat || m.name == "bmp-tracker";
  });
  auto pumpUntil = [&](const std::function<bool()>& done, double timeout_s) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
    while (!done() && std::chrono::steady_clock::now() < end) node.handle(20);
    return done();
  };
  ChildProcess child({test::binPath("bmp-tracker"), "--config", test::sourceDir() + "/config/tracker.yaml",
                      "--lcm-url", url, "--trajectory", trajectory, "--keyframe-trajectory", keyframes},
                     ChildProcess::Output::kFile, log_path);
  ASSERT_TRUE(pumpUntil([&] { return heartbeat || !child.running(); }, 30.0))
      << "no heartbeat; log " << log_path;
  ASSERT_TRUE(child.running()) << "bmp-tracker exited; log " << log_path;

  const capture::SequenceIndex index = capture::indexSequence(test::bonnDir());
  const int n = 40;
  for (int i = 0; i < n; ++i) {
    const auto& pair = index.frames[i];
    rgbd_frame_t msg;
    msg.seq = i;
    msg.utime = static_cast<int64_t>(pair.rgb_stamp * 1e6 + 0.5);
    msg.depth_utime = static_cast<int64_t>(pair.depth_stamp * 1e6 + 0.5);
    msg.source = "rgbd_bonn_crowd";
    msg.camera = bonnCamera();
    msg.depth_scale = 5000.0;
    msg.color = test::fileImage(pair.rgb_path, PixelFormat::kBgr8);
    msg.depth = test::fileImage(pair.depth_path, PixelFormat::kMono16);
    node.publish("RGBD_FRAME", msg);
    // Lockstep, as bmp-capture does it: the next frame once this one is answered.
    ASSERT_TRUE(pumpUntil([&] { return static_cast<int>(poses.size()) > i; }, 20.0)) << "no pose for " << i;
  }
  for (int i = 0; i < n; ++i) {
    EXPECT_EQ(poses[i].seq, i);
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

  EXPECT_EQ(child.stop(20.0), 0) << "log " << log_path;
  const Trajectory written = readTumTrajectory(trajectory);
  EXPECT_EQ(written.size(), static_cast<std::size_t>(n));
  EXPECT_GE(readTumTrajectory(keyframes).size(), 1u);
}

}  // namespace
}  // namespace bmp

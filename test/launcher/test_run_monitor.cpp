// The run summary from what the processes publish: states counted, timing of tracked and detected frames
// only (skipped answers carry no time), the pace from pose to pose, and the files' formats.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <thread>

#include <bmp/detections_t.hpp>
#include <bmp/slam_pose_t.hpp>

#include "bmp/lcm/lcm_node.hpp"
#include "launcher/run_monitor.hpp"
#include "lcm_url.hpp"

namespace bmp::launcher {
namespace {

TEST(RunMonitor, CountsStatesAndTimesWhatWasProcessed) {
  const std::string url = test::uniqueLcmUrl(0);
  RunMonitor monitor(url, "SLAM_POSE", "DETECTIONS");
  LcmNode publisher(url);
  const int8_t states[] = {slam_pose_t::STATE_INITIALISING,
                           slam_pose_t::STATE_OK,
                           slam_pose_t::STATE_OK,
                           slam_pose_t::STATE_LOST,
                           slam_pose_t::STATE_RELOCALISED,
                           slam_pose_t::STATE_SKIPPED,
                           slam_pose_t::STATE_OK};
  int seq = 0;
  for (const int8_t state : states) {
    slam_pose_t pose{};
    pose.seq = seq;
    pose.state = state;
    pose.processing_ms = state == slam_pose_t::STATE_SKIPPED ? 0.0f : 10.0f + static_cast<float>(seq);
    publisher.publish("SLAM_POSE", pose);
    detections_t det{};
    det.seq = seq;
    det.inference_ms = 20.0f;
    if (seq == 3) det.skipped = "colour image: not a JPEG";
    publisher.publish("DETECTIONS", det);
    ++seq;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  RunSummary s;
  for (int i = 0; i < 100 && (s = monitor.summary()).detections < seq; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  EXPECT_EQ(s.poses, 7);
  EXPECT_EQ(s.initialising, 1);
  EXPECT_EQ(s.ok, 3);
  EXPECT_EQ(s.lost, 1);
  EXPECT_EQ(s.relocalised, 1);
  EXPECT_EQ(s.skipped, 1);
  EXPECT_EQ(s.tracking_ms.count(), 6u);            // not the skipped frame
  EXPECT_DOUBLE_EQ(s.tracking_ms.median(), 12.5);  // 10, 11, 12, 13, 14, 16
  EXPECT_EQ(s.detections, 7);
  EXPECT_EQ(s.detections_skipped, 1);
  EXPECT_EQ(s.detector_ms.count(), 6u);
  EXPECT_EQ(s.frame_period_ms.count(), 6u);
  EXPECT_GE(s.frame_period_ms.median(), 15.0);  // published 20 ms apart
  EXPECT_LT(s.answered_per_second(), 70.0);

  const std::string json = formatSummaryJson(s);
  EXPECT_NE(json.find("\"frames\": 7, \"ok\": 3"), std::string::npos) << json;
  EXPECT_NE(json.find("\"skipped\": 1, \"per_frame_ms\""), std::string::npos) << json;
  const std::string text = formatSummaryText(s);
  EXPECT_NE(text.find("7 frames answered: 3 ok, 1 relocalised, 1 lost"), std::string::npos) << text;
}

TEST(RunMonitor, NothingHeardIsAnEmptySummary) {
  RunMonitor monitor(test::uniqueLcmUrl(1), "SLAM_POSE", "DETECTIONS");
  const RunSummary s = monitor.summary();
  EXPECT_EQ(s.poses, 0);
  EXPECT_TRUE(std::isnan(s.answered_per_second()));
  EXPECT_NE(formatSummaryJson(s).find("\"frames_per_second\": null"), std::string::npos);
}

}  // namespace
}  // namespace bmp::launcher

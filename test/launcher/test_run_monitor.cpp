// The run summary from what the processes publish: states counted, timing of tracked and detected frames
// only (skipped answers carry no time), the pace from pose to pose, and the files' formats.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <thread>

#include <bmp/detections_t.hpp>
#include <bmp/process_status_t.hpp>
#include <bmp/slam_pose_t.hpp>

#include "bmp/common/timing.hpp"
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
  const Stopwatch published;
  for (const int8_t state : states) {
    slam_pose_t pose{};
    pose.seq = seq;
    pose.state = state;
    pose.processing_ms = state == slam_pose_t::STATE_SKIPPED ? 0.0f : 10.0f + static_cast<float>(seq);
    const bool posed = state == slam_pose_t::STATE_OK || state == slam_pose_t::STATE_RELOCALISED;
    pose.position_std_m = posed ? 0.001f * static_cast<float>(seq) : -1.0f;  // -1: none
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
  EXPECT_EQ(s.tracking_ms.count(), 6u);                // not the skipped frame
  EXPECT_DOUBLE_EQ(s.tracking_ms.median(), 12.5);      // 10, 11, 12, 13, 14, 16
  EXPECT_EQ(s.position_std_mm.count(), 4u);            // the ok and relocalised frames
  EXPECT_NEAR(s.position_std_mm.median(), 3.0, 1e-3);  // 1, 2, 4, 6 mm
  EXPECT_EQ(s.detections, 7);
  EXPECT_EQ(s.detections_skipped, 1);
  EXPECT_EQ(s.detector_ms.count(), 6u);
  EXPECT_EQ(s.frame_period_ms.count(), 6u);
  // Periods are measured where the poses are heard: on a loaded machine several may be read at once, so
  // only their number is certain here, and that they span no more than the test's own wall time.
  EXPECT_GT(s.frame_period_ms.median(), 0.0);
  EXPECT_LE(s.frame_period_ms.median(), published.elapsedMs());

  const std::string json = formatSummaryJson(s);
  EXPECT_NE(json.find("\"frames\": 7, \"ok\": 3"), std::string::npos) << json;
  EXPECT_NE(json.find("\"skipped\": 1, \"per_frame_ms\""), std::string::npos) << json;
  const std::string text = formatSummaryText(s);
  EXPECT_NE(text.find("7 frames answered: 3 ok, 1 relocalised, 0 degraded, 1 lost"), std::string::npos)
      << text;
  EXPECT_NE(text.find("position std median 3.0 mm"), std::string::npos) << text;
  EXPECT_NE(json.find("\"position_std_mm\": {\"count\": 4"), std::string::npos) << json;
}

// Another publisher's NaN, infinite or negative times count as answers but stay out of the medians.
TEST(RunMonitor, ImplausibleTimesAreLeftOutOfTheMedians) {
  const std::string url = test::uniqueLcmUrl(3);
  RunMonitor monitor(url, "SLAM_POSE", "DETECTIONS");
  LcmNode publisher(url);
  const float times[] = {10.0f, std::nanf(""), -1.0f, INFINITY};
  for (int seq = 0; seq < 4; ++seq) {
    slam_pose_t pose{};
    pose.seq = seq;
    pose.state = slam_pose_t::STATE_OK;
    pose.processing_ms = times[seq];
    publisher.publish("SLAM_POSE", pose);
    detections_t det{};
    det.seq = seq;
    det.inference_ms = times[3 - seq];  // 10 ms last
    publisher.publish("DETECTIONS", det);
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  RunSummary s;
  for (int i = 0; i < 100 && (s = monitor.summary()).detections < 4; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  EXPECT_EQ(s.poses, 4);
  EXPECT_EQ(s.ok, 4);
  EXPECT_EQ(s.detections, 4);
  ASSERT_EQ(s.tracking_ms.count(), 1u);
  EXPECT_DOUBLE_EQ(s.tracking_ms.median(), 10.0);
  ASSERT_EQ(s.detector_ms.count(), 1u);
  EXPECT_DOUBLE_EQ(s.detector_ms.median(), 10.0);
}

// Each process's last heartbeat, by name and instance: how many frames it received, processed, dropped, lost
// and refused, in the text and the JSON; the mapper's own figures from its message; degraded poses counted.
TEST(RunMonitor, KeepsEachProcessLastHeartbeat) {
  const std::string url = test::uniqueLcmUrl(2);
  RunMonitor monitor(url, "SLAM_POSE", "DETECTIONS", "PROCESS_STATUS");
  LcmNode publisher(url);
  const auto beat = [&](const std::string& name, int64_t instance, int8_t state, int64_t base) {
    process_status_t m{};
    m.name = name;
    m.instance = instance;
    m.state = state;
    m.received = base;
    m.processed = base - 10;
    m.dropped = 4;
    m.lost = 5;
    m.malformed = 1;
    m.message = name == "bmp-mapper" ? "12 keyframes, 3400 points, 180 MiB" : "";
    publisher.publish("PROCESS_STATUS", m);
  };
  beat("bmp-tracker", 7, process_status_t::STATE_RUNNING, 50);
  beat("bmp-tracker", 7, process_status_t::STATE_FINISHED, 100);  // replaces the one before
  beat("bmp-tracker", 9, process_status_t::STATE_FINISHED, 30);   // another start of that name
  beat("bmp-mapper", 3, process_status_t::STATE_FINISHED, 12);
  slam_pose_t pose{};
  pose.state = slam_pose_t::STATE_DEGRADED;
  publisher.publish("SLAM_POSE", pose);
  publisher.raw().publish("PROCESS_STATUS", "junk", 4);  // counted as malformed, never a process
  RunSummary s;
  for (int i = 0; i < 100 && ((s = monitor.summary()).processes.size() < 3 || s.poses < 1); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  ASSERT_EQ(s.processes.size(), 3u);
  const ProcessFigures& t = s.processes.at({"bmp-tracker", 7});
  EXPECT_EQ(t.received, 100);
  EXPECT_EQ(t.processed, 90);
  EXPECT_EQ(s.degraded, 1);
  EXPECT_EQ(s.ok, 0);
  const std::string text = formatSummaryText(s);
  EXPECT_NE(
      text.find("bmp-tracker: 100 received, 90 processed, 4 dropped (own queue), 5 lost (never arrived), "
                "1 malformed or refused"),
      std::string::npos)
      << text;
  EXPECT_NE(text.find("bmp-tracker (2): 30 received"), std::string::npos) << text;
  EXPECT_NE(text.find("mapper:    12 keyframes, 3400 points, 180 MiB"), std::string::npos) << text;
  EXPECT_NE(text.find("1 degraded"), std::string::npos) << text;
  const std::string json = formatSummaryJson(s);
  EXPECT_NE(json.find("{\"name\": \"bmp-tracker\", \"finished\": true, \"received\": 100, \"processed\": 90, "
                      "\"dropped\": 4, \"lost\": 5, \"malformed\": 1"),
            std::string::npos)
      << json;
  EXPECT_NE(json.find("\"degraded\": 1"), std::string::npos) << json;
}

TEST(RunMonitor, NothingHeardIsAnEmptySummary) {
  RunMonitor monitor(test::uniqueLcmUrl(1), "SLAM_POSE", "DETECTIONS");
  const RunSummary s = monitor.summary();
  EXPECT_EQ(s.poses, 0);
  EXPECT_TRUE(std::isnan(s.answered_per_second()));
  EXPECT_NE(formatSummaryJson(s).find("\"frames_per_second\": null"), std::string::npos);
  // The printed summary is for people: no JSON null there (a run that stopped before two poses).
  const std::string text = formatSummaryText(s);
  EXPECT_EQ(text.find("null"), std::string::npos) << text;
  EXPECT_NE(text.find("end to end: - (fewer than two poses)"), std::string::npos) << text;
}

}  // namespace
}  // namespace bmp::launcher

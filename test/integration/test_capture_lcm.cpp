// bmp-capture and tum2lcm over a real udpm:// URL into a consumer in another process.
#include <gtest/gtest.h>

#include <cmath>
#include <csignal>
#include <filesystem>
#include <thread>

#include "bmp/common/child_process.hpp"
#include "bmp/lcm/lcm_node.hpp"
#include "capture/lcm/frame_message.hpp"
#include "capture/tum_sequence.hpp"
#include "integration_support.hpp"

namespace bmp {
namespace {

namespace fs = std::filesystem;
using test::binPath;

struct Played {
  std::vector<test::ReportLine> frames;
  int capture_status = -1;
  std::string capture_log;
};

// Starts the listener, plays Bonn through bmp-capture with the given extra arguments, returns what arrived.
Played playBonn(const std::string& name, int slot, std::vector<std::string> capture_args, bool ack,
                double timeout_s) {
  const fs::path dir = test::scratchDir(name);
  const std::string url = test::uniqueLcmUrl(slot);
  const std::string report = (dir / "report.txt").string();
  std::vector<std::string> listener_args{
      binPath("bmp-test-listener"), "--lcm-url", url, "--report", report, "--decode"};
  if (ack) listener_args.push_back("--ack");
  ChildProcess listener(listener_args, ChildProcess::Output::kFile, (dir / "listener.log").string());
  std::vector<std::string> args{binPath("bmp-capture"), "--lcm-url",        url, "--dataset", test::bonnDir(),
                                "--wait-for",           "bmp-test-listener"};
  args.insert(args.end(), capture_args.begin(), capture_args.end());
  ChildProcess capture(args, ChildProcess::Output::kFile, (dir / "capture.log").string());
  Played played;
  played.capture_status = capture.wait(timeout_s).value_or(-1);
  std::this_thread::sleep_for(std::chrono::milliseconds(500));  // the last datagrams are in flight
  EXPECT_EQ(listener.stop(5.0), 0) << test::readText((dir / "listener.log").string());
  played.frames = test::readReport(report);
  played.capture_log = test::readText((dir / "capture.log").string());
  return played;
}

// Every associated frame, in order, with the dataset's stamps, both images intact.
void expectEveryFrame(const Played& played) {
  const capture::SequenceIndex index = capture::indexSequence(test::bonnDir());
  ASSERT_EQ(played.capture_status, 0) << played.capture_log;
  ASSERT_EQ(played.frames.size(), index.frames.size()) << "frames lost or duplicated\n" << played.capture_log;
  for (std::size_t i = 0; i < played.frames.size(); ++i) {
    const auto& f = played.frames[i];
    ASSERT_EQ(f.seq, static_cast<long long>(i));
    EXPECT_EQ(f.utime, capture::secondsToUtime(index.frames[i].rgb_stamp));
    EXPECT_EQ(f.depth_utime, capture::secondsToUtime(index.frames[i].depth_stamp));
    EXPECT_EQ(f.color_bytes, static_cast<long long>(fs::file_size(index.frames[i].rgb_path)));
    EXPECT_EQ(f.decoded, 1);
  }
  // The dataset's six missing depth files are reported, not fatal.
  EXPECT_NE(played.capture_log.find("listed but does not exist"), std::string::npos);
}

TEST(CaptureOverLcm, BonnLockstepDeliversEveryFrame) {
  expectEveryFrame(playBonn("lcm_lockstep", 0, {"--mode", "lockstep"}, true, 180));
}

TEST(CaptureOverLcm, BonnRealtimeDeliversEveryFrame) {
  const Played played = playBonn("lcm_realtime", 1, {"--mode", "realtime"}, false, 120);
  expectEveryFrame(played);
  // Real time: 927 frames recorded over about 31 s must take about that long to play.
  EXPECT_NE(played.capture_log.find("published 927 frames in 3"), std::string::npos) << played.capture_log;
}

TEST(CaptureOverLcm, Tum2LcmLogReplaysThroughLcmLogplayer) {
  const fs::path dir = test::scratchDir("lcm_logplayer");
  const std::string log = (dir / "bonn.lcmlog").string();
  ChildProcess convert({binPath("tum2lcm"), "--dataset", test::bonnDir(), "--out", log},
                       ChildProcess::Output::kFile, (dir / "tum2lcm.log").string());
  ASSERT_EQ(convert.wait(120).value_or(-1), 0) << test::readText((dir / "tum2lcm.log").string());
  const std::string url = test::uniqueLcmUrl(2);
  const std::string report = (dir / "report.txt").string();
  ChildProcess listener({binPath("bmp-test-listener"), "--lcm-url", url, "--report", report, "--decode"},
                        ChildProcess::Output::kFile, (dir / "listener.log").string());
  std::this_thread::sleep_for(std::chrono::seconds(1));  // lcm-logplayer does not wait for listeners
  ChildProcess player({"/usr/bin/lcm-logplayer", "--lcm-url=" + url, "--speed=2", log},
                      ChildProcess::Output::kFile, (dir / "player.log").string());
  ASSERT_EQ(player.wait(120).value_or(-1), 0) << test::readText((dir / "player.log").string());
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  EXPECT_EQ(listener.stop(5.0), 0);
  Played played;
  played.capture_status = 0;
  played.frames = test::readReport(report);
  played.capture_log = test::readText((dir / "tum2lcm.log").string());
  expectEveryFrame(played);
}

// Garbage from another publisher on the lockstep answer channel: warned about, counted, the run goes on.
TEST(CaptureOverLcm, MalformedMessagesOnAckChannelAreSkipped) {
  const fs::path dir = test::scratchDir("lcm_malformed");
  const std::string url = test::uniqueLcmUrl(3);
  const std::string report = (dir / "report.txt").string();
  ChildProcess listener({binPath("bmp-test-listener"), "--lcm-url", url, "--report", report, "--ack"},
                        ChildProcess::Output::kFile, (dir / "listener.log").string());
  ChildProcess capture({binPath("bmp-capture"), "--lcm-url", url, "--dataset", test::bonnDir(), "--mode",
                        "lockstep", "--end", "120", "--wait-for", "bmp-test-listener"},
                       ChildProcess::Output::kFile, (dir / "capture.log").string());
  LcmNode intruder(url);
  const char garbage[] = "\x01\x02 not a slam_pose_t";
  for (int i = 0; i < 20 && capture.running(); ++i) {
    intruder.raw().publish("SLAM_POSE", garbage, sizeof(garbage));
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ASSERT_EQ(capture.wait(60).value_or(-1), 0) << test::readText((dir / "capture.log").string());
  listener.stop(5.0);
  const std::string log = test::readText((dir / "capture.log").string());
  EXPECT_NE(log.find("malformed message on channel SLAM_POSE"), std::string::npos) << log;
  EXPECT_EQ(test::readReport(report).size(), 120u);
}

// Lockstep with two answer channels waits for the slower consumer on each frame: a detector-like listener
// that answers DETECTIONS 30 ms late sets the pace although the tracker-like one answers SLAM_POSE at once.
// Both listeners have one name: "--wait-for name,name" waits for two of them.
TEST(CaptureOverLcm, LockstepWaitsForEveryAnswerChannel) {
  const fs::path dir = test::scratchDir("lcm_two_acks");
  const std::string url = test::uniqueLcmUrl(10);
  const int frames = 60, delay_ms = 30;
  ChildProcess fast(
      {binPath("bmp-test-listener"), "--lcm-url", url, "--report", (dir / "fast.txt").string(), "--ack"},
      ChildProcess::Output::kFile, (dir / "fast.log").string());
  ChildProcess slow({binPath("bmp-test-listener"), "--lcm-url", url, "--report", (dir / "slow.txt").string(),
                     "--ack-detections", "--ack-delay-ms", std::to_string(delay_ms)},
                    ChildProcess::Output::kFile, (dir / "slow.log").string());
  ChildProcess capture({binPath("bmp-capture"), "--lcm-url", url, "--dataset", test::bonnDir(), "--mode",
                        "lockstep", "--end", std::to_string(frames), "--ack-channels", "SLAM_POSE,DETECTIONS",
                        "--wait-for", "bmp-test-listener,bmp-test-listener"},
                       ChildProcess::Output::kFile, (dir / "capture.log").string());
  ASSERT_EQ(capture.wait(60).value_or(-1), 0) << test::readText((dir / "capture.log").string());
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  fast.stop(5.0);
  slow.stop(5.0);
  const std::string log = test::readText((dir / "capture.log").string());
  EXPECT_EQ(test::readReport((dir / "fast.txt").string()).size(), static_cast<std::size_t>(frames));
  EXPECT_EQ(test::readReport((dir / "slow.txt").string()).size(), static_cast<std::size_t>(frames));
  EXPECT_EQ(log.find("lockstep timeouts"), std::string::npos) << log;
  // Waiting for the slow answer on every frame takes at least frames x delay; without it, a few ms a frame.
  const auto at = log.find("frames in ");
  ASSERT_NE(at, std::string::npos) << log;
  const double seconds = std::stod(log.substr(at + 10));
  EXPECT_GE(seconds, 0.9 * frames * delay_ms / 1000.0) << log;
}

// Two consumers of one name, the second started well after capture: "--wait-for name,name" holds the first
// frame until both are heard, so each answers every frame. Waiting by name alone, the first listener's
// heartbeats released capture while the second was not yet listening (frame 0 then timed out on DETECTIONS).
TEST(CaptureOverLcm, WaitForTwoConsumersOfOneNameHoldsUntilBothListen) {
  const fs::path dir = test::scratchDir("lcm_same_name");
  const std::string url = test::uniqueLcmUrl(12);
  const int frames = 40;
  ChildProcess tracker_like(
      {binPath("bmp-test-listener"), "--lcm-url", url, "--report", (dir / "pose.txt").string(), "--ack"},
      ChildProcess::Output::kFile, (dir / "pose.log").string());
  ChildProcess capture({binPath("bmp-capture"), "--lcm-url", url, "--dataset", test::bonnDir(), "--mode",
                        "lockstep", "--end", std::to_string(frames), "--ack-channels", "SLAM_POSE,DETECTIONS",
                        "--wait-for", "bmp-test-listener,bmp-test-listener"},
                       ChildProcess::Output::kFile, (dir / "capture.log").string());
  // Several heartbeats of the first listener go by meanwhile; none may count twice.
  std::this_thread::sleep_for(std::chrono::milliseconds(2500));
  ASSERT_TRUE(capture.running()) << test::readText((dir / "capture.log").string());
  ChildProcess detector_like({binPath("bmp-test-listener"), "--lcm-url", url, "--report",
                              (dir / "detections.txt").string(), "--ack-detections"},
                             ChildProcess::Output::kFile, (dir / "detections.log").string());
  ASSERT_EQ(capture.wait(60).value_or(-1), 0) << test::readText((dir / "capture.log").string());
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  tracker_like.stop(5.0);
  detector_like.stop(5.0);
  const std::string log = test::readText((dir / "capture.log").string());
  EXPECT_NE(log.find("published " + std::to_string(frames) + " frames"), std::string::npos) << log;
  EXPECT_EQ(log.find("lockstep timeouts"), std::string::npos) << log;
  EXPECT_EQ(log.find("no answer on"), std::string::npos) << log;
  EXPECT_EQ(test::readReport((dir / "pose.txt").string()).size(), static_cast<std::size_t>(frames));
  EXPECT_EQ(test::readReport((dir / "detections.txt").string()).size(), static_cast<std::size_t>(frames));
}

// A channel that never answers costs one timeout per frame, and the warning names it.
TEST(CaptureOverLcm, LockstepTimeoutNamesTheSilentChannel) {
  const fs::path dir = test::scratchDir("lcm_silent_ack");
  const std::string url = test::uniqueLcmUrl(11);
  const std::string config = (dir / "capture.yaml").string();
  std::ofstream(config) << "capture:\n  lockstep_timeout_s: 0.3\n";
  ChildProcess listener(
      {binPath("bmp-test-listener"), "--lcm-url", url, "--report", (dir / "r.txt").string(), "--ack"},
      ChildProcess::Output::kFile, (dir / "listener.log").string());
  ChildProcess capture(
      {binPath("bmp-capture"), "--config", config, "--lcm-url", url, "--dataset", test::bonnDir(), "--mode",
       "lockstep", "--end", "3", "--ack-channels", "SLAM_POSE,DETECTIONS", "--wait-for", "bmp-test-listener"},
      ChildProcess::Output::kFile, (dir / "capture.log").string());
  ASSERT_EQ(capture.wait(60).value_or(-1), 0) << test::readText((dir / "capture.log").string());
  listener.stop(5.0);
  const std::string log = test::readText((dir / "capture.log").string());
  EXPECT_NE(log.find("no answer on DETECTIONS for frame 0"), std::string::npos) << log;
  EXPECT_EQ(log.find("no answer on SLAM_POSE"), std::string::npos) << log;
  EXPECT_NE(log.find("lockstep timeouts 3"), std::string::npos) << log;
}

}  // namespace
}  // namespace bmp

// bmp-capture and tum2lcm over a real udpm:// URL into a consumer in another process.
#include <gtest/gtest.h>

#include <cmath>
#include <csignal>
#include <filesystem>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <bmp/detections_t.hpp>
#include <bmp/process_status_t.hpp>
#include <bmp/rgbd_frame_t.hpp>
#include <bmp/slam_pose_t.hpp>

#include "bmp/common/child_process.hpp"
#include "bmp/common/stamp.hpp"
#include "bmp/common/tum_trajectory.hpp"
#include "bmp/lcm/channels.hpp"
#include "bmp/lcm/lcm_node.hpp"
#include "capture/lcm/frame_message.hpp"
#include "capture/tum_sequence.hpp"
#include "integration_support.hpp"
#include "run_command.hpp"

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
// Only a lockstep listener (ack) decodes both images of every frame: without flow control, decoding 30 frames
// a second on a loaded machine would let the kernel drop frames, which is not what these tests look for
// (LostFrames counts such losses); the bytes of every frame are checked all the same.
Played playBonn(const std::string& name, int slot, std::vector<std::string> capture_args, bool ack,
                double timeout_s) {
  const fs::path dir = test::scratchDir(name);
  const std::string url = test::uniqueLcmUrl(slot);
  const std::string report = (dir / "report.txt").string();
  std::vector<std::string> listener_args{binPath("bmp-test-listener"), "--lcm-url", url, "--report", report};
  if (ack) listener_args.insert(listener_args.end(), {"--ack", "--decode"});
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
    EXPECT_EQ(f.utime, secondsToUtime(index.frames[i].rgb_stamp));
    EXPECT_EQ(f.depth_utime, secondsToUtime(index.frames[i].depth_stamp));
    EXPECT_EQ(f.color_bytes, static_cast<long long>(fs::file_size(index.frames[i].rgb_path)));
    EXPECT_EQ(f.decoded, 1);
  }
  // The dataset's six missing depth files are reported, not fatal.
  EXPECT_NE(played.capture_log.find("listed but does not exist"), std::string::npos);
}

TEST(CaptureOverLcm, BonnLockstepDeliversEveryFrame) {
  const Played played = playBonn("lcm_lockstep", 0, {"--mode", "lockstep"}, true, 180);
  expectEveryFrame(played);
  // Capture names five of the six missing files, and counts the sixth: no later warning would.
  EXPECT_NE(played.capture_log.find("1 more skipped frame(s) not named above"), std::string::npos)
      << played.capture_log;
}

TEST(CaptureOverLcm, BonnRealtimeDeliversEveryFrame) {
  const Played played = playBonn("lcm_realtime", 1, {"--mode", "realtime"}, false, 120);
  expectEveryFrame(played);
  // Real time: 927 frames recorded over about 31 s must take about that long to play.
  EXPECT_NE(played.capture_log.find("published 927 frames in 3"), std::string::npos) << played.capture_log;
}

// Whether a heartbeat of the named process is heard on url within timeout_s: it subscribes before its first
// heartbeat and sends one a second, so once heard it listens.
bool heartbeatHeard(const std::string& url, const std::string& name, double timeout_s) {
  LcmNode node(url);
  bool heard = false;
  node.subscribe<process_status_t>(
      channels::kProcessStatus,
      [&](const process_status_t& m, const ReceivedInfo&) { heard |= m.name == name; });
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (!heard && std::chrono::steady_clock::now() < until) node.handle(100);
  return heard;
}

TEST(CaptureOverLcm, Tum2LcmLogReplaysThroughLcmLogplayer) {
  const fs::path dir = test::scratchDir("lcm_logplayer");
  const std::string log = (dir / "bonn.lcmlog").string();
  ChildProcess convert({binPath("tum2lcm"), "--dataset", test::bonnDir(), "--out", log},
                       ChildProcess::Output::kFile, (dir / "tum2lcm.log").string());
  ASSERT_EQ(convert.wait(120).value_or(-1), 0) << test::readText((dir / "tum2lcm.log").string());
  const std::string url = test::uniqueLcmUrl(2);
  const std::string report = (dir / "report.txt").string();
  // No decoding: lcm-logplayer has no flow control (see playBonn).
  ChildProcess listener({binPath("bmp-test-listener"), "--lcm-url", url, "--report", report},
                        ChildProcess::Output::kFile, (dir / "listener.log").string());
  // lcm-logplayer does not wait for listeners (a fixed second raced the listener's start under load).
  ASSERT_TRUE(heartbeatHeard(url, "bmp-test-listener", 30.0))
      << test::readText((dir / "listener.log").string());
  ChildProcess player({"/usr/bin/lcm-logplayer", "--lcm-url=" + url, "--speed=1", log},
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
// --loop with --groundtruth-out (as bmp-run --frames N --loop K passes them): each pass's ground truth is
// its own frames' stretch, shifted as the pass is, so the file runs forward in time and a frame pairs with
// its own pass's pose. The whole dataset's ground truth once per pass made the passes overlap (found by
// review: the file went back in time at each pass).
TEST(CaptureOverLcm, LoopedGroundTruthRunsForwardOnePassAfterAnother) {
  const fs::path dir = test::scratchDir("capture_loop_truth");
  const std::string out = (dir / "groundtruth.txt").string();
  const test::Outcome o = test::runCommand(
      "capture_loop_truth",
      {binPath("bmp-capture"), "--lcm-url", test::uniqueLcmUrl(9), "--dataset", test::bonnDir(), "--mode",
       "fast", "--end", "20", "--loop", "3", "--groundtruth-out", out},
      120);
  ASSERT_EQ(o.status, 0) << o.output;
  const Trajectory truth = readTumTrajectory(out);
  const capture::SequenceIndex index = capture::indexSequence(test::bonnDir());
  const double first = index.frames[0].rgb_stamp, last = index.frames[19].rgb_stamp;
  const double period = (last - first) * 20.0 / 19.0;  // a pass: its frames and one mean interval
  Trajectory one_pass;
  for (const auto& p : index.groundtruth)
    if (p.stamp >= first - 0.5 * period / 20 && p.stamp < first + period - 0.5 * period / 20)
      one_pass.push_back(p);
  ASSERT_GE(one_pass.size(), 15u);
  ASSERT_EQ(truth.size(), 3 * one_pass.size()) << o.output;
  for (std::size_t i = 1; i < truth.size(); ++i)
    ASSERT_GT(truth[i].stamp, truth[i - 1].stamp) << "pose " << i;
  for (int pass = 0; pass < 3; ++pass)
    for (std::size_t i = 0; i < one_pass.size(); ++i) {
      const auto& p = truth[pass * one_pass.size() + i];
      EXPECT_NEAR(p.stamp, one_pass[i].stamp + pass * period, 1e-3);
      EXPECT_TRUE(p.T_world_cam.isApprox(one_pass[i].T_world_cam, 1e-6));
    }
}

TEST(CaptureOverLcm, MalformedMessagesOnAckChannelAreSkipped) {
  const fs::path dir = test::scratchDir("lcm_malformed");
  const std::string url = test::uniqueLcmUrl(3);
  const std::string report = (dir / "report.txt").string();
  // Answers 20 ms late: playing takes 2.4 s or more, so the garbage sent all along meets a capture that
  // listens (garbage sent before it plays reaches nobody; an instant run would be over before any arrives).
  ChildProcess listener(
      {binPath("bmp-test-listener"), "--lcm-url", url, "--report", report, "--ack", "--ack-delay-ms", "20"},
      ChildProcess::Output::kFile, (dir / "listener.log").string());
  ChildProcess capture({binPath("bmp-capture"), "--lcm-url", url, "--dataset", test::bonnDir(), "--mode",
                        "lockstep", "--end", "120", "--wait-for", "bmp-test-listener"},
                       ChildProcess::Output::kFile, (dir / "capture.log").string());
  LcmNode intruder(url);
  const char garbage[] = "\x01\x02 not a slam_pose_t";
  for (int i = 0; i < 6000 && capture.running(); ++i) {
    intruder.raw().publish("SLAM_POSE", garbage, sizeof(garbage));
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ASSERT_EQ(capture.wait(60).value_or(-1), 0) << test::readText((dir / "capture.log").string());
  listener.stop(5.0);
  const std::string log = test::readText((dir / "capture.log").string());
  EXPECT_NE(log.find("malformed message on channel SLAM_POSE"), std::string::npos) << log;
  EXPECT_EQ(log.find("no answer on"), std::string::npos) << log;
  EXPECT_EQ(test::readReport(report).size(), 120u);
}

// Forged answers (the frame's seq with another stamp, seq = INT64_MAX, the next frame's seq) never release a
// lockstep frame: each next frame goes out only after the real answers to the one before, on both channels.
TEST(CaptureOverLcm, LockstepIgnoresForgedAnswers) {
  const fs::path dir = test::scratchDir("lcm_forged_answers");
  const std::string url = test::uniqueLcmUrl(13);
  const int frames = 20;
  ChildProcess listener({binPath("bmp-test-listener"), "--lcm-url", url, "--report", (dir / "r.txt").string(),
                         "--ack", "--ack-detections", "--ack-delay-ms", "100"},
                        ChildProcess::Output::kFile, (dir / "listener.log").string());
  ChildProcess capture(
      {binPath("bmp-capture"), "--lcm-url", url, "--dataset", test::bonnDir(), "--mode", "lockstep", "--end",
       std::to_string(frames), "--ack-channels", "SLAM_POSE,DETECTIONS", "--wait-for", "bmp-test-listener"},
      ChildProcess::Output::kFile, (dir / "capture.log").string());
  LcmNode lcm(url, [](const std::string&) {});
  std::map<int64_t, int64_t> sent;  // seq -> utime of the frames capture published
  std::map<int64_t, int> answered;  // seq -> real answers heard (pose and detections)
  std::vector<std::string> order_errors;
  int forged = 0;
  lcm.subscribe<rgbd_frame_t>("RGBD_FRAME", [&](const rgbd_frame_t& m, const ReceivedInfo&) {
    if (m.seq > 0 && answered[m.seq - 1] < 2) order_errors.push_back("frame " + std::to_string(m.seq));
    sent[m.seq] = m.utime;
    for (const auto& [seq, utime] : {std::pair<int64_t, int64_t>{m.seq, m.utime + 1},
                                     {std::numeric_limits<int64_t>::max(), m.utime},
                                     {m.seq + 1, m.utime}}) {
      slam_pose_t pose{};
      pose.seq = seq;
      pose.utime = utime;
      lcm.publish("SLAM_POSE", pose);
      detections_t det{};
      det.seq = seq;
      det.utime = utime;
      det.model = "forged";
      lcm.publish("DETECTIONS", det);
      forged += 2;
    }
  });
  const auto real = [&](int64_t seq, int64_t utime) {
    const auto it = sent.find(seq);
    if (it != sent.end() && it->second == utime) ++answered[seq];
  };
  lcm.subscribe<slam_pose_t>("SLAM_POSE",
                             [&](const slam_pose_t& m, const ReceivedInfo&) { real(m.seq, m.utime); });
  lcm.subscribe<detections_t>("DETECTIONS",
                              [&](const detections_t& m, const ReceivedInfo&) { real(m.seq, m.utime); });
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (capture.running() && std::chrono::steady_clock::now() < deadline) lcm.handle(10);
  ASSERT_EQ(capture.wait(10).value_or(-1), 0);
  listener.stop(5.0);
  const std::string log = test::readText((dir / "capture.log").string());
  EXPECT_EQ(sent.size(), static_cast<std::size_t>(frames));
  EXPECT_TRUE(order_errors.empty()) << "published before the real answers: " << order_errors.front();
  EXPECT_EQ(log.find("no answer on"), std::string::npos) << log;
  // Every forgery is counted but the last frame's, which may come after the real answers let capture finish
  // (when this process is slower than the listener's 100 ms delay).
  const std::string counted = "answers ignored (not for a frame we sent) ";
  const auto at = log.find(counted);
  ASSERT_NE(at, std::string::npos) << log;
  const long ignored = std::stol(log.substr(at + counted.size()));
  EXPECT_LE(ignored, forged) << log;
  EXPECT_GE(ignored, forged - 6) << "forged " << forged << "\n" << log;
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

// A frame lost on its way to the consumer (here: ignored on its first arrival, as a kernel buffer overflowed
// by someone's huge message would drop it) is published again once its answer is late, so lockstep goes
// on after a fraction of a second instead of the 5 s timeout, and the consumer sees every frame.
TEST(CaptureOverLcm, LockstepResendsAFrameWhoseAnswerIsLate) {
  const fs::path dir = test::scratchDir("lcm_resend");
  const std::string url = test::uniqueLcmUrl(14);
  const int frames = 30;
  ChildProcess listener({binPath("bmp-test-listener"), "--lcm-url", url, "--report",
                         (dir / "pose.txt").string(), "--ack", "--ignore-once", "12"},
                        ChildProcess::Output::kFile, (dir / "listener.log").string());
  ChildProcess capture({binPath("bmp-capture"), "--lcm-url", url, "--dataset", test::bonnDir(), "--mode",
                        "lockstep", "--end", std::to_string(frames), "--wait-for", "bmp-test-listener"},
                       ChildProcess::Output::kFile, (dir / "capture.log").string());
  ASSERT_EQ(capture.wait(60).value_or(-1), 0) << test::readText((dir / "capture.log").string());
  listener.stop(5.0);
  const std::string log = test::readText((dir / "capture.log").string());
  EXPECT_EQ(log.find("no answer on"), std::string::npos) << log;
  EXPECT_NE(log.find("resent (answers late) "), std::string::npos) << log;
  const auto report = test::readReport((dir / "pose.txt").string());
  ASSERT_EQ(report.size(), static_cast<std::size_t>(frames));
  for (int i = 0; i < frames; ++i) EXPECT_EQ(report[static_cast<std::size_t>(i)].seq, i);
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
  // Long enough that the listener's SLAM_POSE answer always comes within it, even on a loaded machine.
  std::ofstream(config) << "capture:\n  lockstep_timeout_s: 2.0\n";
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
  // One warning per frame, naming only the silent channel (several silent ones are named in one line).
  std::vector<std::string> warnings;
  std::istringstream lines(log);
  for (std::string line; std::getline(lines, line);)
    if (const auto at = line.find("no answer on "); at != std::string::npos)
      warnings.push_back(line.substr(at));
  ASSERT_EQ(warnings.size(), 3u) << log;
  for (std::size_t seq = 0; seq < warnings.size(); ++seq)
    EXPECT_EQ(warnings[seq].rfind("no answer on DETECTIONS for frame " + std::to_string(seq) + " within", 0),
              0u)
        << warnings[seq];
  EXPECT_NE(log.find("lockstep timeouts 3"), std::string::npos) << log;
}

}  // namespace
}  // namespace bmp

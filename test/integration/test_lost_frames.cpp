// Every frame a real-time publisher sent is accounted for by the tracker: answered (tracked or refused),
// dropped from its own queue, or counted as lost (a gap in seq): after a 3 s SIGSTOP of the tracker, and in
// an lcm-logplayer replay. The numbers are compared exactly: from the tracker's final heartbeat, the poses
// the test heard, and what the publisher sent.
#include <gtest/gtest.h>

#include <csignal>
#include <filesystem>
#include <map>
#include <thread>

#include <lcm/lcm-cpp.hpp>

#include <bmp/process_status_t.hpp>
#include <bmp/slam_pose_t.hpp>

#include "bmp/common/child_process.hpp"
#include "bmp/lcm/lcm_node.hpp"
#include "integration_support.hpp"

namespace bmp {
namespace {

namespace fs = std::filesystem;
using test::binPath;

// A real-time bmp-tracker (no detector, policy latest, exits once idle) and what the test hears of it. Idle
// for 10 s: the SIGSTOP below lasts 3 s, or longer when this test is slow to send SIGCONT on a loaded
// machine, and the idle clock runs on through it.
class WatchedTracker {
 public:
  WatchedTracker(const fs::path& dir, const std::string& url) : dir_(dir), lcm_(url) {
    lcm_.subscribe<slam_pose_t>("SLAM_POSE", [this](const slam_pose_t&, const ReceivedInfo&) { ++poses; });
    lcm_.subscribe<process_status_t>(
        "PROCESS_STATUS", [this](const process_status_t& m, const ReceivedInfo&) { last[m.name] = m; });
    child_ = std::make_unique<ChildProcess>(
        std::vector<std::string>{binPath("bmp-tracker"), "--config",
                                 test::sourceDir() + "/config/tracker.yaml", "--lcm-url", url,
                                 "--frame-policy", "latest", "--dynamic-mode", "none", "--idle-exit", "10"},
        ChildProcess::Output::kFile, (dir / "tracker.log").string());
  }
  ChildProcess& child() { return *child_; }
  // Handles LCM for seconds (or until done), so the test's own socket never backs up.
  bool pumpFor(
      double seconds, const std::function<bool()>& done = [] { return false; }) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (!done() && std::chrono::steady_clock::now() < end) lcm_.handle(20);
    return done();
  }
  bool finished(const std::string& name) const {
    const auto it = last.find(name);
    return it != last.end() && it->second.state == process_status_t::STATE_FINISHED;
  }
  std::string log() const { return test::readText((dir_ / "tracker.log").string()); }

  int64_t poses = 0;
  std::map<std::string, process_status_t> last;

 private:
  fs::path dir_;
  LcmNode lcm_;
  std::unique_ptr<ChildProcess> child_;
};

// published = answered + dropped + lost, and what the tracker says it answered is what the test heard.
void expectEveryFrameCounted(const WatchedTracker& t, int64_t published) {
  ASSERT_TRUE(t.finished("bmp-tracker")) << t.log();
  const process_status_t& s = t.last.at("bmp-tracker");
  EXPECT_EQ(s.processed + s.malformed, t.poses) << t.log();
  EXPECT_EQ(s.received, s.processed + s.malformed + s.dropped) << t.log();
  EXPECT_EQ(published, t.poses + s.dropped + s.lost)
      << "answered " << t.poses << ", dropped " << s.dropped << ", lost " << s.lost << "\n"
      << t.log();
}

TEST(LostFrames, TrackerStoppedForThreeSecondsCountsEveryFrame) {
  const fs::path dir = test::scratchDir("lost_sigstop");
  const std::string url = test::uniqueLcmUrl(0);
  WatchedTracker t(dir, url);
  ASSERT_TRUE(t.pumpFor(30, [&] { return t.last.count("bmp-tracker") > 0; })) << t.log();
  ChildProcess capture({binPath("bmp-capture"), "--lcm-url", url, "--dataset", test::bonnDir(), "--mode",
                        "realtime", "--speed", "1", "--end", "300", "--wait-for", "bmp-tracker"},
                       ChildProcess::Output::kFile, (dir / "capture.log").string());
  ASSERT_TRUE(t.pumpFor(60, [&] { return t.poses >= 60; })) << t.log();
  t.child().signal(SIGSTOP);
  t.pumpFor(3.0);
  t.child().signal(SIGCONT);
  t.pumpFor(60, [&] { return t.finished("bmp-capture"); });
  ASSERT_EQ(capture.wait(30).value_or(-1), 0) << test::readText((dir / "capture.log").string());
  t.pumpFor(60, [&] { return t.finished("bmp-tracker"); });
  EXPECT_EQ(t.child().wait(20).value_or(-1), 0) << t.log();
  const process_status_t& c = t.last.at("bmp-capture");
  EXPECT_EQ(c.processed, 300);  // frames published (Bonn's first 300 have both images)
  const process_status_t& s = t.last.at("bmp-tracker");
  EXPECT_GT(s.dropped + s.lost, 30) << "3 s at 30 Hz stopped, yet few frames missed";
  expectEveryFrameCounted(t, c.processed);
}

// Frames in an LCM log, counted by reading it.
int64_t framesInLog(const std::string& path) {
  lcm::LogFile log(path, "r");
  int64_t n = 0;
  while (const lcm::LogEvent* e = log.readNextEvent()) n += e->channel == "RGBD_FRAME";
  return n;
}

TEST(LostFrames, LogplayerReplayCountsEveryFrame) {
  const fs::path dir = test::scratchDir("lost_logplayer");
  const std::string log = (dir / "bonn.lcmlog").string();
  ChildProcess convert({binPath("tum2lcm"), "--dataset", test::bonnDir(), "--out", log, "--end", "400"},
                       ChildProcess::Output::kFile, (dir / "tum2lcm.log").string());
  ASSERT_EQ(convert.wait(120).value_or(-1), 0) << test::readText((dir / "tum2lcm.log").string());
  const int64_t in_log = framesInLog(log);
  ASSERT_GT(in_log, 390);
  const std::string url = test::uniqueLcmUrl(1);
  WatchedTracker t(dir, url);
  ASSERT_TRUE(t.pumpFor(30, [&] { return t.last.count("bmp-tracker") > 0; })) << t.log();
  // Twice the recorded rate: on a loaded machine the tracker falls behind, and frames go missing.
  ChildProcess player({"/usr/bin/lcm-logplayer", "--lcm-url=" + url, "--speed=2", log},
                      ChildProcess::Output::kFile, (dir / "player.log").string());
  t.pumpFor(120, [&] { return !player.running(); });
  ASSERT_EQ(player.wait(10).value_or(-1), 0) << test::readText((dir / "player.log").string());
  t.pumpFor(60, [&] { return t.finished("bmp-tracker"); });
  EXPECT_EQ(t.child().wait(20).value_or(-1), 0) << t.log();
  expectEveryFrameCounted(t, in_log);
}

}  // namespace
}  // namespace bmp

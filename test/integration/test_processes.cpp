// Process-level behaviour: --help everywhere, configuration and input errors, and the launcher.
#include <gtest/gtest.h>

#include <signal.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "bmp/common/child_process.hpp"
#include "bmp/common/tum_trajectory.hpp"
#include "integration_support.hpp"

namespace bmp {
namespace {

namespace fs = std::filesystem;
using test::binPath;

using test::Outcome;
using test::runCommand;

// Every executable we ship answers --help with a usage text and exit status 0.
TEST(Processes, EveryBinaryAnswersHelp) {
  int checked = 0;
  for (const auto& entry : fs::directory_iterator(test::binaryDir() + "/bin")) {
    const std::string name = entry.path().filename().string();
    const bool shipped = name.rfind("bmp-", 0) == 0 || name == "tum2lcm";  // not the gtest executables
    if (!shipped) continue;
    const Outcome o = runCommand("help_" + name, {entry.path().string(), "--help"}, 30);
    EXPECT_EQ(o.status, 0) << name << ": " << o.output;
    EXPECT_NE(o.output.find("Usage"), std::string::npos) << name << ": " << o.output;
    ++checked;
  }
  // capture, detector, tracker, run, eval, detect, synth, tum2lcm, the benchmarks and the test listener
  EXPECT_GE(checked, 10);
}

// lcm-spy decodes a channel only with its type's class on the classpath: every struct of lcmtypes/ must be in
// the generated jar, and the jars tools/spy puts beside it installed.
TEST(Processes, SpyHasEveryMessageType) {
  const Outcome o = runCommand("spy_check", {"/usr/bin/env", "BMP_BUILD_DIR=" + test::binaryDir(),
                                             test::sourceDir() + "/tools/spy", "--check"});
  EXPECT_EQ(o.status, 0) << o.output;
  for (const char* type : {"rgbd_frame_t", "detections_t", "slam_pose_t", "keyframe_t", "keyframe_poses_t",
                           "octomap_t", "occupancy_grid_t", "point_cloud_t", "process_status_t"})
    EXPECT_NE(o.output.find(std::string("ok       bmp.") + type), std::string::npos) << type << "\n"
                                                                                     << o.output;
}

TEST(Processes, UnknownConfigKeyIsRefusedWithFileAndKey) {
  const fs::path dir = test::scratchDir("bad_config");
  std::ofstream(dir / "capture.yaml") << "capture:\n  mode: fast\n  sped: 2.0\n";
  const Outcome o =
      runCommand("bad_config", {binPath("bmp-capture"), "--config", (dir / "capture.yaml").string(),
                                "--dataset", test::bonnDir(), "--lcm-url", "memq://"});
  EXPECT_EQ(o.status, 2) << o.output;
  EXPECT_NE(o.output.find("capture.sped"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find((dir / "capture.yaml").string()), std::string::npos) << o.output;
}

TEST(Processes, MissingDatasetAndBadOptionsAreClearErrors) {
  const Outcome missing = runCommand(
      "missing_dataset", {binPath("bmp-capture"), "--dataset", "/nonexistent/seq", "--lcm-url", "memq://"});
  EXPECT_EQ(missing.status, 1);
  EXPECT_NE(missing.output.find("/nonexistent/seq"), std::string::npos) << missing.output;
  const Outcome bad_mode =
      runCommand("bad_mode", {binPath("bmp-capture"), "--mode", "slow", "--lcm-url", "memq://"});
  EXPECT_NE(bad_mode.status, 0);
  EXPECT_NE(bad_mode.output.find("slow"), std::string::npos) << bad_mode.output;
  const Outcome unknown = runCommand("unknown_option", {binPath("bmp-capture"), "--frobnicate"});
  EXPECT_EQ(unknown.status, 2);
  EXPECT_NE(unknown.output.find("--frobnicate"), std::string::npos) << unknown.output;
  // Lockstep with nothing to wait for would play as fast as it can: refused before any frame.
  const Outcome no_ack = runCommand("lockstep_no_ack", {binPath("bmp-capture"), "--mode", "lockstep",
                                                        "--ack-channels", "", "--lcm-url", "memq://"});
  EXPECT_EQ(no_ack.status, 2);
  EXPECT_NE(no_ack.output.find("needs at least one answer channel"), std::string::npos) << no_ack.output;
  // A count below its range once meant something quietly: --idle-exit -1 never exited, --bench -2 printed
  // nan.
  const Outcome idle =
      runCommand("idle_exit", {binPath("bmp-tracker"), "--idle-exit", "-1", "--lcm-url", "memq://"});
  EXPECT_EQ(idle.status, 2) << idle.output;
  EXPECT_NE(idle.output.find("--idle-exit must be a number of at least 0, got '-1'"), std::string::npos)
      << idle.output;
  const Outcome bench = runCommand("synth_bench", {binPath("bmp-synth"), "--bench", "-2"});
  EXPECT_EQ(bench.status, 2) << bench.output;
  EXPECT_NE(bench.output.find("--bench must be an integer from 1 to"), std::string::npos) << bench.output;
}

// A selection past the end played or wrote nothing and ended with exit 1 and no reason; tum2lcm also emptied
// the log already at --out. Each now says why, and tum2lcm writes beside --out, renaming only a whole log.
TEST(Processes, NothingToPlayOrWriteIsSaidAndLeavesAnEarlierLogAsItWas) {
  const fs::path dir = test::scratchDir("nothing_to_play");
  const std::string log = (dir / "frames.lcmlog").string();
  std::ofstream(log) << "an earlier log";
  const Outcome exists = runCommand(
      "tum2lcm_exists", {binPath("tum2lcm"), "--dataset", test::bonnDir(), "--out", log, "--end", "2"});
  EXPECT_EQ(exists.status, 2) << exists.output;
  EXPECT_NE(exists.output.find("--out '" + log + "' exists; give --force to replace it"), std::string::npos)
      << exists.output;
  EXPECT_EQ(test::readText(log), "an earlier log");
  const Outcome past = runCommand("tum2lcm_past_end", {binPath("tum2lcm"), "--dataset", test::bonnDir(),
                                                       "--out", log, "--start", "5000", "--force"});
  EXPECT_EQ(past.status, 2) << past.output;  // a usage error, as bmp-capture's (was 1)
  EXPECT_NE(past.output.find("--start 5000 is past the end of"), std::string::npos) << past.output;
  EXPECT_EQ(test::readText(log), "an earlier log");
  EXPECT_FALSE(fs::exists(log + ".partial"));
  for (const auto& [option, value] : std::vector<std::pair<std::string, std::string>>{
           {"--channel", ""}, {"--max-diff", "-1"}, {"--every", "0"}, {"--verify", "full"}}) {
    const Outcome bad = runCommand("tum2lcm_bad_option", {binPath("tum2lcm"), "--dataset", test::bonnDir(),
                                                          "--out", log, "--force", option, value});
    EXPECT_EQ(bad.status, 2) << option << ": " << bad.output;
    EXPECT_NE(bad.output.find(option), std::string::npos) << bad.output;
    EXPECT_EQ(test::readText(log), "an earlier log") << option;
  }
  const Outcome capture = runCommand(
      "capture_past_end",
      {binPath("bmp-capture"), "--dataset", test::bonnDir(), "--start", "5000", "--lcm-url", "memq://"});
  EXPECT_EQ(capture.status, 2) << capture.output;
  EXPECT_NE(capture.output.find("--start 5000 is past the end of"), std::string::npos) << capture.output;
  // A link planted where tum2lcm writes its partial log: the link goes, the file it named is untouched (it
  // was overwritten with the log). A folder as --out is refused before converting (it failed at the end).
  const std::string other = (dir / "other.txt").string();
  std::ofstream(other) << "not to be overwritten";
  fs::create_symlink(other, log + ".partial");
  const Outcome linked =
      runCommand("tum2lcm_linked_partial",
                 {binPath("tum2lcm"), "--dataset", test::bonnDir(), "--out", log, "--force", "--end", "3"});
  EXPECT_EQ(linked.status, 0) << linked.output;
  EXPECT_EQ(test::readText(other), "not to be overwritten");
  EXPECT_GT(fs::file_size(log), 1000u);
  EXPECT_FALSE(fs::is_symlink(log));
  fs::create_directories(dir / "a_folder");
  const Outcome folder =
      runCommand("tum2lcm_folder_out", {binPath("tum2lcm"), "--dataset", test::bonnDir(), "--out",
                                        (dir / "a_folder").string(), "--force", "--end", "3"});
  EXPECT_EQ(folder.status, 2) << folder.output;
  EXPECT_NE(folder.output.find("is a folder; give a file name"), std::string::npos) << folder.output;
  // A camera of another size: every frame is skipped, but only the first few are named one by one (the end's
  // count has them all), not a warning per frame.
  std::ofstream(dir / "small.yaml") << "camera: {width: 320, height: 240, fx: 271.4, fy: 271.3, cx: 157.8, "
                                       "cy: 118.9, distortion: [0, 0, 0, 0, 0], depth_scale: 5000}\n";
  const Outcome small =
      runCommand("capture_wrong_size",
                 {binPath("bmp-capture"), "--dataset", test::bonnDir(), "--camera",
                  (dir / "small.yaml").string(), "--end", "40", "--mode", "fast", "--lcm-url", "memq://"});
  EXPECT_EQ(small.status, 1) << small.output;
  std::size_t named = 0;
  for (std::size_t at = small.output.find("the camera is 320x240"); at != std::string::npos;
       at = small.output.find("the camera is 320x240", at + 1))
    ++named;
  EXPECT_GE(named, 1u) << small.output;
  EXPECT_LE(named, 6u) << small.output;
  EXPECT_NE(small.output.find("published 0 frames"), std::string::npos) << small.output;
}

// A killed consumer must not take the data with it: capture in realtime mode finishes on its own.
TEST(Processes, CaptureSurvivesItsConsumerBeingKilled) {
  const fs::path dir = test::scratchDir("killed_consumer");
  const std::string url = test::uniqueLcmUrl(4);
  ChildProcess listener(
      {binPath("bmp-test-listener"), "--lcm-url", url, "--report", (dir / "r.txt").string()},
      ChildProcess::Output::kFile, (dir / "listener.log").string());
  ChildProcess capture({binPath("bmp-capture"), "--lcm-url", url, "--dataset", test::bonnDir(), "--mode",
                        "realtime", "--speed", "4", "--end", "200", "--wait-for", "bmp-test-listener"},
                       ChildProcess::Output::kFile, (dir / "capture.log").string());
  // Killed once capture has heard it and plays (a fixed sleep raced the listener's start on a loaded machine:
  // killed before its first heartbeat, capture waited for it in vain).
  const auto playing = [&] {
    return test::readText((dir / "capture.log").string()).find("playing ") != std::string::npos;
  };
  for (int i = 0; i < 600 && !playing(); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  ASSERT_TRUE(playing()) << test::readText((dir / "capture.log").string());
  listener.signal(SIGKILL);
  EXPECT_EQ(capture.wait(60).value_or(-1), 0) << test::readText((dir / "capture.log").string());
}

fs::path writeRunConfig(const fs::path& dir, const std::string& listener_args) {
  std::ofstream(dir / "run.yaml")
      << "run:\n  output_root: " << (dir / "out").string()
      << "\n  mode: lockstep\n  drain_s: 0.2\n  stop_timeout_s: 5.0\n  evaluate: true\n"
      << "  processes:\n    bmp-test-listener: " << listener_args << "\n  capture_args: []\n";
  return dir / "run.yaml";
}

TEST(Launcher, RunsProcessesPlaysAndGathersOutputs) {
  const fs::path dir = test::scratchDir("launcher_ok");
  const fs::path config = writeRunConfig(dir, "[--ack, --report, \"{out}/listener.txt\"]");
  const fs::path out = dir / "run";
  const Outcome o = runCommand("launcher_ok",
                               {binPath("bmp-run"), "--config", config.string(), "--dataset", test::bonnDir(),
                                "--frames", "40", "--out", out.string(), "--lcm-url", test::uniqueLcmUrl(5)},
                               120);
  ASSERT_EQ(o.status, 0) << o.output;
  EXPECT_EQ(test::readReport((out / "listener.txt").string()).size(), 40u);
  EXPECT_TRUE(fs::exists(out / "logs" / "bmp-capture.log"));
  EXPECT_TRUE(fs::exists(out / "logs" / "bmp-test-listener.log"));
  EXPECT_EQ(readTumTrajectory((out / "groundtruth.txt").string()).size(), 933u);
}

TEST(Launcher, SyntheticDefaultPlaysWithGroundTruth) {
  const fs::path dir = test::scratchDir("launcher_synthetic");
  const fs::path config = writeRunConfig(dir, "[--ack, --decode, --report, \"{out}/listener.txt\"]");
  const fs::path out = dir / "run";
  const Outcome o = runCommand("launcher_synthetic",
                               {binPath("bmp-run"), "--config", config.string(), "--frames", "30", "--out",
                                out.string(), "--lcm-url", test::uniqueLcmUrl(6)},
                               120);
  ASSERT_EQ(o.status, 0) << o.output;
  const auto frames = test::readReport((out / "listener.txt").string());
  ASSERT_EQ(frames.size(), 30u);
  for (const auto& f : frames) EXPECT_EQ(f.decoded, 1);
  EXPECT_EQ(readTumTrajectory((out / "groundtruth.txt").string()).size(), 30u);
}

// The shipped run configuration: capture, detector and tracker over LCM, then the evaluation.
TEST(Launcher, FullPipelineOnBonnTracksAndEvaluates) {
  const fs::path out = test::scratchDir("launcher_pipeline") / "run";
  const Outcome o = runCommand("launcher_pipeline",
                               {binPath("bmp-run"), "--dataset", test::bonnDir(), "--frames", "90", "--out",
                                out.string(), "--lcm-url", test::uniqueLcmUrl(8)},
                               240);
  ASSERT_EQ(o.status, 0) << o.output;
  const Trajectory trajectory = readTumTrajectory((out / "trajectory.txt").string());
  EXPECT_EQ(trajectory.size(), 90u);  // lockstep: a pose for every frame
  EXPECT_FALSE(readTumTrajectory((out / "keyframes.txt").string()).empty());
  // The tracker's frame log: a line per frame, each with the detector's own boxes (lockstep waits for them)
  // and no frame missed.
  const auto logged = test::readTsvRows((out / "frames.tsv").string());
  ASSERT_EQ(logged.size(), 90u);
  for (std::size_t i = 0; i < logged.size(); ++i) {
    const auto& fields = logged[i];
    ASSERT_EQ(fields.size(), 22u) << "line " << i;
    EXPECT_EQ(fields[1], std::to_string(i));  // seq
    EXPECT_EQ(fields[2], "OK") << "line " << i;
    EXPECT_EQ(fields[14], "0") << "line " << i;    // frames missed
    EXPECT_EQ(fields[15], "own") << "line " << i;  // boxes
    if (i == 0) continue;                          // the map's first frame: no pose solved, no position std
    // Hundreds of inliers over a room: the position pinned to millimetres, not centimetres.
    EXPECT_GT(std::stod(fields[21]), 0.0) << "line " << i;
    EXPECT_LT(std::stod(fields[21]), 20.0) << "line " << i;
  }
  const std::string eval = test::readText((out / "eval.json").string());
  const auto ate_at = eval.find("\"ate\"");
  ASSERT_NE(ate_at, std::string::npos) << eval;
  // Lockstep is reproducible (boxes waited for, mapping inline): the same 90 frames give the same
  // trajectory on every run, 7.4 mm when this was written, so the bound can be tight.
  const auto rmse_at = eval.find("\"rmse\": ", ate_at);
  ASSERT_NE(rmse_at, std::string::npos) << eval;
  const double ate_rmse = std::stod(eval.substr(rmse_at + 8));
  EXPECT_LT(ate_rmse, 0.009) << eval;
  EXPECT_GT(ate_rmse, 0.0) << eval;
  // Bonn's ground truth is a motion-capture marker's pose: the evaluation says its RPE is not meaningful.
  EXPECT_NE(eval.find("\"meaningful\": false"), std::string::npos) << eval;
  EXPECT_NE(eval.find("\"constant\": true"), std::string::npos) << eval;
  EXPECT_NE(o.output.find("not camera orientations"), std::string::npos) << o.output;
  EXPECT_TRUE(fs::exists(out / "plots"));
  // The frame log drawn beside the error plots (bmp-eval --frame-log).
  ASSERT_TRUE(fs::exists(out / "plots" / "trajectory_frames.png")) << o.output;
  EXPECT_GT(fs::file_size(out / "plots" / "trajectory_frames.png"), 10'000u);
  // The run summary heard every frame's answers, with the processes' own timing.
  const std::string summary = test::readText((out / "summary.json").string());
  EXPECT_NE(summary.find("\"tracker\": {\"frames\": 90"), std::string::npos) << summary;
  EXPECT_NE(summary.find("\"detector\": {\"frames\": 90, \"skipped\": 0"), std::string::npos) << summary;
  EXPECT_NE(o.output.find("end to end:"), std::string::npos) << o.output;
  // The detector answered every frame (lockstep runs it in 'every' mode).
  const std::string detector_log = test::readText((out / "logs" / "bmp-detector.log").string());
  EXPECT_NE(detector_log.find("processed 90"), std::string::npos) << detector_log;
}

TEST(Launcher, FailingProcessFailsTheRun) {
  const fs::path dir = test::scratchDir("launcher_fail");
  const fs::path config = writeRunConfig(dir, "[--no-such-option]");
  const Outcome o =
      runCommand("launcher_fail",
                 {binPath("bmp-run"), "--config", config.string(), "--dataset", test::bonnDir(), "--frames",
                  "40", "--out", (dir / "run").string(), "--lcm-url", test::uniqueLcmUrl(7)},
                 120);
  EXPECT_NE(o.status, 0) << o.output;
  EXPECT_NE(o.output.find("bmp-test-listener ended early"), std::string::npos) << o.output;
}

// A tracker killed mid-run (SIGKILL: no chance to write on exit) fails the run, and its poses up to then are
// kept in the run folder and evaluated.
TEST(Launcher, KilledTrackerFailsTheRunAndItsPosesAreKept) {
  const fs::path dir = test::scratchDir("launcher_killed_tracker");
  test::trackerOnlyRunConfig(dir, dir / "out", "--trajectory, \"{out}/trajectory.txt\"");
  const fs::path out = dir / "run";
  const fs::path log = dir / "bmp-run.log";
  ChildProcess run({binPath("bmp-run"), "--config", (dir / "run.yaml").string(), "--dataset", test::bonnDir(),
                    "--frames", "400", "--out", out.string(), "--lcm-url", test::uniqueLcmUrl(9)},
                   ChildProcess::Output::kFile, log.string());
  const fs::path trajectory = out / "trajectory.txt";
  const auto poses = [&] {
    try {
      return fs::exists(trajectory) ? readTumTrajectory(trajectory.string()).size() : std::size_t{0};
    } catch (const TrajectoryError&) {
      return std::size_t{0};  // a line being written
    }
  };
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(90);
  while (poses() < 20 && run.running() && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  ASSERT_GE(poses(), 20u) << test::readText(log.string());
  const pid_t tracker = test::findProcess("bmp-tracker", out.string());
  ASSERT_GT(tracker, 0) << "bmp-tracker not found";
  ASSERT_EQ(::kill(tracker, SIGKILL), 0);

  const int status = run.wait(120).value_or(-1);
  const std::string output = test::readText(log.string());
  EXPECT_NE(status, 0) << output;
  EXPECT_NE(output.find("bmp-tracker ended early"), std::string::npos) << output;
  const std::size_t kept = poses();
  EXPECT_GE(kept, 20u);
  EXPECT_LT(kept, 400u);  // killed well before the end
  EXPECT_NE(test::readText((out / "eval.json").string()).find("\"ate\""), std::string::npos) << output;
}

// A run of bmp-run (tracker only, lockstep) on Bonn, with its log, for the tests that kill one of its
// processes once the tracker has written `poses` poses.
struct KillableRun {
  fs::path dir, out, log;
  std::unique_ptr<ChildProcess> run;
  explicit KillableRun(const std::string& name, int slot) : dir(test::scratchDir(name)), out(dir / "run") {
    test::trackerOnlyRunConfig(dir, dir / "out",
                               "--trajectory, \"{out}/trajectory.txt\", --frame-policy, every");
    log = dir / "bmp-run.log";
    run = std::make_unique<ChildProcess>(
        std::vector<std::string>{binPath("bmp-run"), "--config", (dir / "run.yaml").string(), "--dataset",
                                 test::bonnDir(), "--frames", "400", "--out", out.string(), "--lcm-url",
                                 test::uniqueLcmUrl(slot)},
        ChildProcess::Output::kFile, log.string());
  }
  std::size_t poses() const {
    const fs::path trajectory = out / "trajectory.txt";
    try {
      return fs::exists(trajectory) ? readTumTrajectory(trajectory.string()).size() : std::size_t{0};
    } catch (const TrajectoryError&) {
      return std::size_t{0};  // a line being written
    }
  }
  bool waitForPoses(std::size_t n) const {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(90);
    while (poses() < n && run->running() && std::chrono::steady_clock::now() < deadline)
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    return poses() >= n;
  }
};

// Capture killed mid-run: the run fails, but the dataset's ground truth was written before the first frame,
// so the poses tracked so far are still evaluated.
TEST(Launcher, CaptureKilledMidRunStillEvaluates) {
  KillableRun r("launcher_killed_capture", 10);
  ASSERT_TRUE(r.waitForPoses(20)) << test::readText(r.log.string());
  const pid_t capture = test::findProcess("bmp-capture", r.out.string());
  ASSERT_GT(capture, 0) << "bmp-capture not found";
  ASSERT_EQ(::kill(capture, SIGKILL), 0);
  const int status = r.run->wait(120).value_or(-1);
  const std::string output = test::readText(r.log.string());
  EXPECT_NE(status, 0) << output;
  EXPECT_GE(r.poses(), 20u);
  EXPECT_NE(test::readText((r.out / "eval.json").string()).find("\"ate\""), std::string::npos) << output;
}

// bmp-run killed outright (SIGKILL: it cannot stop anyone): its children get SIGTERM from the kernel
// (parent-death signal) and exit cleanly, the tracker replacing its live poses with the optimised ones.
TEST(Launcher, KilledLauncherStopsItsChildrenCleanly) {
  KillableRun r("launcher_killed_itself", 11);
  ASSERT_TRUE(r.waitForPoses(20)) << test::readText(r.log.string());
  const pid_t tracker = test::findProcess("bmp-tracker", r.out.string());
  const pid_t capture = test::findProcess("bmp-capture", r.out.string());
  ASSERT_GT(tracker, 0);
  ASSERT_GT(capture, 0);
  EXPECT_NE(test::readFirstLine((r.out / "trajectory.txt").string()).find("live poses"), std::string::npos);
  r.run->signal(SIGKILL);
  ASSERT_TRUE(r.run->wait(10).has_value());
  // Not our children: gone from /proc (or a zombie of init's) when they have exited.
  const auto gone = [](pid_t pid) {
    const std::string stat = test::readText("/proc/" + std::to_string(pid) + "/stat");
    return stat.empty() || stat.find(") Z") != std::string::npos;
  };
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while ((!gone(tracker) || !gone(capture)) && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  EXPECT_TRUE(gone(tracker)) << "bmp-tracker still running";
  EXPECT_TRUE(gone(capture)) << "bmp-capture still running";
  EXPECT_EQ(test::readFirstLine((r.out / "trajectory.txt").string()), "# timestamp tx ty tz qx qy qz qw");
  EXPECT_GE(r.poses(), 20u);
}

}  // namespace
}  // namespace bmp

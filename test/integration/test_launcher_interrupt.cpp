// Ctrl-C on bmp-run: the run is stopped by the user, not failed. What was tracked is kept and evaluated,
// and bmp-run exits 130 as a shell expects of an interrupted command.
#include <gtest/gtest.h>

#include <signal.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include "bmp/common/child_process.hpp"
#include "bmp/common/tum_trajectory.hpp"
#include "integration_support.hpp"

namespace bmp {
namespace {

namespace fs = std::filesystem;
using test::binPath;

std::size_t poses(const fs::path& trajectory) {
  try {
    return fs::exists(trajectory) ? readTumTrajectory(trajectory.string()).size() : 0;
  } catch (const TrajectoryError&) {
    return 0;  // a line being written
  }
}

// A terminal's Ctrl-C reaches bmp-run and every process of the run: sent here to each, bmp-run first.
TEST(LauncherInterrupt, CtrlCStopsTheRunWithoutCallingItFailed) {
  const fs::path dir = test::scratchDir("launcher_interrupt");
  test::trackerOnlyRunConfig(dir, dir / "root",
                             "--trajectory, \"{out}/trajectory.txt\", --frame-policy, every");
  const fs::path out = dir / "run";
  const fs::path log = dir / "bmp-run.log";
  ChildProcess run({binPath("bmp-run"), "--config", (dir / "run.yaml").string(), "--dataset", test::bonnDir(),
                    "--frames", "400", "--out", out.string(), "--lcm-url", test::uniqueLcmUrl(12)},
                   ChildProcess::Output::kFile, log.string());
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(90);
  while (poses(out / "trajectory.txt") < 20 && run.running() && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  ASSERT_GE(poses(out / "trajectory.txt"), 20u) << test::readText(log.string());
  const pid_t tracker = test::findProcess("bmp-tracker", out.string());
  const pid_t capture = test::findProcess("bmp-capture", out.string());
  ASSERT_GT(tracker, 0);
  ASSERT_GT(capture, 0);
  run.signal(SIGINT);
  ::kill(capture, SIGINT);
  ::kill(tracker, SIGINT);

  const int status = run.wait(120).value_or(-1);
  const std::string output = test::readText(log.string());
  EXPECT_EQ(status, 130) << output;
  EXPECT_NE(output.find("run stopped by the user"), std::string::npos) << output;
  EXPECT_EQ(output.find("FAILED"), std::string::npos) << output;
  EXPECT_EQ(output.find("a process failed"), std::string::npos) << output;
  EXPECT_EQ(output.find("ended early"), std::string::npos) << output;
  EXPECT_GE(poses(out / "trajectory.txt"), 20u);
  EXPECT_NE(test::readText((out / "eval.json").string()).find("\"ate\""), std::string::npos) << output;
  EXPECT_TRUE(fs::exists(out / "summary.json"));
}

}  // namespace
}  // namespace bmp

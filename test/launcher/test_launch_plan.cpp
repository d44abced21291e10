#include <gtest/gtest.h>

#include <algorithm>

#include "launcher/launch_plan.hpp"

namespace bmp::launcher {
namespace {

RunSettings settingsFrom(const std::string& yaml) {
  const Config c = Config::fromString(yaml, "run.yaml");
  RunSettings s = runSettingsFromConfig(c.section("run"));
  c.finish();
  return s;
}

bool contains(const std::vector<std::string>& argv, const std::vector<std::string>& seq) {
  return std::search(argv.begin(), argv.end(), seq.begin(), seq.end()) != argv.end();
}

TEST(LaunchPlan, ProcessesInOrderWithExpandedPlaceholders) {
  const RunSettings s = settingsFrom(
      "run:\n  mode: lockstep\n  processes:\n    bmp-detector: [--mode, \"{frame_policy}\"]\n"
      "    bmp-tracker: [--trajectory, \"{out}/trajectory.txt\"]\n");
  RunRequest r;
  r.out_dir = "/runs/r1";
  r.bin_dir = "/opt/bin";
  r.lcm_url = "udpm://x";
  r.dataset = "/data/seq";
  r.frames = 50;
  const LaunchPlan plan = makePlan(s, r);
  ASSERT_EQ(plan.processes.size(), 2u);
  EXPECT_EQ(plan.processes[0].name, "bmp-detector");
  EXPECT_EQ(plan.processes[0].argv[0], "/opt/bin/bmp-detector");
  EXPECT_TRUE(contains(plan.processes[0].argv, {"--mode", "every"}));
  EXPECT_TRUE(contains(plan.processes[1].argv, {"--trajectory", "/runs/r1/trajectory.txt"}));
  EXPECT_TRUE(contains(plan.processes[1].argv, {"--lcm-url", "udpm://x"}));
  const auto& cap = plan.capture.argv;
  EXPECT_TRUE(contains(cap, {"--mode", "lockstep"}));
  EXPECT_TRUE(contains(cap, {"--dataset", "/data/seq"}));
  EXPECT_TRUE(contains(cap, {"--end", "50"}));
  EXPECT_TRUE(contains(cap, {"--wait-for", "bmp-detector,bmp-tracker"}));
  EXPECT_EQ(plan.trajectory_path, "/runs/r1/trajectory.txt");
}

TEST(LaunchPlan, RealtimeModeMakesConsumersTakeTheNewestFrame) {
  const RunSettings s = settingsFrom("run:\n  processes:\n    bmp-detector: [--mode, \"{frame_policy}\"]\n");
  RunRequest r;
  r.mode = "realtime";
  const LaunchPlan plan = makePlan(s, r);
  EXPECT_TRUE(contains(plan.processes[0].argv, {"--mode", "latest"}));
  EXPECT_FALSE(contains(plan.capture.argv, {"--dataset"}));  // synthetic scene
}

TEST(LaunchPlan, UnknownRunKeyIsRefused) {
  const Config c = Config::fromString("run:\n  procesess: {}\n", "run.yaml");
  runSettingsFromConfig(c.section("run"));
  EXPECT_THROW(c.finish(), ConfigError);
}

TEST(LaunchPlan, UnknownModeIsRefused) {
  EXPECT_THROW(settingsFrom("run:\n  mode: slow\n"), ConfigError);
  EXPECT_TRUE(isCaptureMode("fast"));
  EXPECT_FALSE(isCaptureMode("bogus"));
}

}  // namespace
}  // namespace bmp::launcher

// The benchmark scripts as a user meets them: --help, arguments refused up front, an exit status that says
// whether the runs worked, and no process left behind.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "integration_support.hpp"

namespace bmp {
namespace {

namespace fs = std::filesystem;
using test::Outcome;
using test::runCommand;

// A script of tools/ run with the test's build folder (and TMPDIR, when given, for its temporary files).
Outcome runScript(const std::string& name, const std::vector<std::string>& args,
                  const std::string& tmpdir = "", double timeout_s = 60) {
  std::vector<std::string> argv = {"/usr/bin/env", "BMP_BUILD_DIR=" + test::binaryDir()};
  if (!tmpdir.empty()) argv.push_back("TMPDIR=" + tmpdir);
  argv.push_back(test::sourceDir() + "/tools/" + name);
  argv.insert(argv.end(), args.begin(), args.end());
  return runCommand(name, argv, timeout_s);
}

// Processes still alive (not zombies) whose command line mentions marker.
std::vector<std::string> livingProcessesMentioning(const std::string& marker) {
  std::vector<std::string> found;
  for (const auto& entry : fs::directory_iterator("/proc")) {
    const std::string pid = entry.path().filename().string();
    if (pid.find_first_not_of("0123456789") != std::string::npos) continue;
    std::string cmdline = test::readText((entry.path() / "cmdline").string());
    std::replace(cmdline.begin(), cmdline.end(), '\0', ' ');
    const std::string stat = test::readText((entry.path() / "stat").string());
    if (cmdline.find(marker) != std::string::npos && stat.find(") Z") == std::string::npos)
      found.push_back(pid + ": " + cmdline);
  }
  return found;
}

// A TUM folder whose lists exist but pair nothing: bmp-capture starts and fails at once.
fs::path brokenSequence(const fs::path& dir) {
  fs::create_directories(dir / "seq");
  std::ofstream(dir / "seq" / "rgb.txt") << "# nothing\n";
  std::ofstream(dir / "seq" / "depth.txt") << "# nothing\n";
  return dir / "seq";
}

// --help used to be taken as the dataset: exit 1, no message, and a listener left running.
TEST(BenchCapture, AnswersHelpAndRefusesBadArguments) {
  const fs::path dir = test::scratchDir("bench_capture_args");
  const Outcome help = runScript("bench-capture", {"--help"}, dir.string());
  EXPECT_EQ(help.status, 0) << help.output;
  EXPECT_NE(help.output.find("Usage: tools/bench-capture"), std::string::npos) << help.output;
  const Outcome no_folder = runScript("bench-capture", {(dir / "missing").string()}, dir.string());
  EXPECT_EQ(no_folder.status, 2) << no_folder.output;
  EXPECT_NE(no_folder.output.find("not a TUM-format folder"), std::string::npos) << no_folder.output;
  const Outcome bad_runs = runScript("bench-capture", {test::bonnDir(), "many"}, dir.string());
  EXPECT_EQ(bad_runs.status, 2) << bad_runs.output;
  EXPECT_TRUE(livingProcessesMentioning(dir.string()).empty());
}

// A capture that fails ends the script under set -e: its listener must not outlive it.
TEST(BenchCapture, FailedCaptureLeavesNoListenerBehind) {
  const fs::path dir = test::scratchDir("bench_capture_cleanup");
  const Outcome o = runScript("bench-capture", {brokenSequence(dir).string(), "1"}, dir.string());
  EXPECT_NE(o.status, 0) << o.output;
  const auto left = livingProcessesMentioning(dir.string());
  EXPECT_TRUE(left.empty()) << left.front();
}

// A misspelt variant or a non-number used to run (and fail) every run, then exit 0.
TEST(Bench, RefusesBadArgumentsBeforeAnyRun) {
  const fs::path dir = test::scratchDir("bench_args");
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"--variants", "bogus"}, "--variants 'bogus'"},
      {{"--frames", "abc"}, "--frames 'abc'"},
      {{"--modes", "slow"}, "--modes 'slow'"},
      {{"--every", "0"}, "--every '0'"},
      {{"--frames"}, "--frames needs a value"}};
  for (const auto& [extra, message] : cases) {
    std::vector<std::string> args = {"--dataset", test::bonnDir(), "--out", (dir / "out").string()};
    args.insert(args.end(), extra.begin(), extra.end());
    const Outcome o = runScript("bench", args);
    EXPECT_EQ(o.status, 2) << extra[0] << ": " << o.output;
    EXPECT_NE(o.output.find(message), std::string::npos) << o.output;
  }
  EXPECT_FALSE(fs::exists(dir / "out"));  // refused before anything was written
}

// Every run failing is the benchmark's failure, not only a column of results.md.
TEST(Bench, FailedRunsMakeTheExitStatusNonZero) {
  const fs::path dir = test::scratchDir("bench_failed_runs");
  const Outcome o = runScript("bench",
                              {"--dataset", brokenSequence(dir).string(), "--variants", "none", "--runs", "1",
                               "--out", (dir / "out").string()},
                              "", 180);
  EXPECT_EQ(o.status, 1) << o.output;
  EXPECT_NE(o.output.find("1 of 1 runs failed"), std::string::npos) << o.output;
}

}  // namespace
}  // namespace bmp

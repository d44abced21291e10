// Runs the bmp-eval executable: exit codes, one-line errors, the written outputs.
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "eval_test_util.hpp"
#include "shared_data.hpp"

namespace bmp::eval {

namespace {
struct CliRun {
  int status = -1;
  std::string out;
  std::string err;
};

CliRun runEval(const std::filesystem::path& dir, const std::string& arguments) {
  const std::string out = (dir / "stdout.txt").string();
  const std::string err = (dir / "stderr.txt").string();
  CliRun r;
  r.status = test::runCommand("'" + bmp::test::binPath("bmp-eval") + "' " + arguments + " >'" + out +
                              "' 2>'" + err + "'");
  r.out = test::readText(out);
  r.err = test::readText(err);
  return r;
}

std::string gtPath() {
  return bmp::test::bonnDir() + "/groundtruth.txt";
}

int lineCount(const std::string& text) {
  return static_cast<int>(std::count(text.begin(), text.end(), '\n'));
}
}  // namespace

TEST(evalCli, SelfComparisonWritesAllOutputs) {
  const auto dir = bmp::test::scratchDir("eval_cli_ok");
  const CliRun r =
      runEval(dir, "--gt '" + gtPath() + "' --est '" + gtPath() + "' --label 'self run/1' --json '" +
                       (dir / "r.json").string() + "' --aligned '" + (dir / "aligned.txt").string() +
                       "' --plot-dir '" + (dir / "plots").string() + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("ATE"), std::string::npos);
  EXPECT_NE(r.out.find("RPE"), std::string::npos);
  EXPECT_NE(r.out.find("rmse        0.000000 m"), std::string::npos) << r.out;
  const std::string json = test::readText((dir / "r.json").string());
  EXPECT_NE(json.find("\"label\": \"self run/1\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"rotation_deg\""), std::string::npos) << json;
  // The label keeps its slash in titles; plot file names get a file-safe version.
  EXPECT_NE(r.out.find("bmp-eval: self run/1"), std::string::npos) << r.out;
  EXPECT_TRUE(std::filesystem::exists(dir / "plots" / "self_run_1_trajectory.png"));
  EXPECT_TRUE(std::filesystem::exists(dir / "plots" / "self_run_1_errors.png"));
  EXPECT_GT(std::filesystem::file_size(dir / "aligned.txt"), 10'000u);
}

TEST(evalCli, GroundTruthCoveringPartOfTheRunIsWarnedAbout) {
  const auto dir = bmp::test::scratchDir("eval_cli_coverage");
  // The ground truth's first half only: the estimate's second half has nothing to be compared with.
  const std::string full = test::readText(gtPath());
  std::size_t cut = 0;
  for (int lines = lineCount(full) / 2; lines > 0; --lines) cut = full.find('\n', cut) + 1;
  const std::string half = (dir / "half.txt").string();
  { std::ofstream(half) << full.substr(0, cut); }
  const CliRun r =
      runEval(dir, "--gt '" + half + "' --est '" + gtPath() + "' --json '" + (dir / "r.json").string() + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("WARNING: only "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("the ATE speaks for that part of the run only"), std::string::npos) << r.out;
  const std::string json = test::readText((dir / "r.json").string());
  const std::size_t at = json.find("\"coverage\": ");
  ASSERT_NE(at, std::string::npos) << json;
  EXPECT_NEAR(std::stod(json.substr(at + 12)), 0.5, 0.02);
  // The whole ground truth: no warning.
  const CliRun whole = runEval(dir, "--gt '" + gtPath() + "' --est '" + gtPath() + "'");
  ASSERT_EQ(whole.status, 0) << whole.err;
  EXPECT_EQ(whole.out.find("WARNING"), std::string::npos) << whole.out;
}

TEST(evalCli, HelpAndBadCommandLine) {
  const auto dir = bmp::test::scratchDir("eval_cli_help");
  const CliRun help = runEval(dir, "--help");
  EXPECT_EQ(help.status, 0);
  EXPECT_NE(help.out.find("--rpe-unit"), std::string::npos) << help.out;
  EXPECT_NE(help.out.find("Example"), std::string::npos) << help.out;
  EXPECT_EQ(runEval(dir, "--gt x").status, 1);
  EXPECT_EQ(runEval(dir, "--gt x --est y --max-diff abc").status, 1);
  const CliRun unit = runEval(dir, "--gt x --est y --rpe-unit m");
  EXPECT_EQ(unit.status, 1);
  EXPECT_NE(unit.err.find("unknown RPE delta unit 'm'"), std::string::npos) << unit.err;
}

// A delta or scale of zero or less gives figures that mean nothing (RPE 0.000 m over a zero interval): the
// command line is refused (bmp-eval's exit 1 for a bad command line), naming the option and its range.
TEST(evalCli, ValuesOutOfRangeAreRefusedNamingTheOption) {
  const auto dir = bmp::test::scratchDir("eval_cli_range");
  const std::pair<const char*, const char*> bad[] = {
      {"rpe-delta", "0"}, {"rpe-delta", "-1"},  {"rpe-delta", "nan"}, {"scale", "0"},
      {"scale", "-2"},    {"max-diff", "-0.1"}, {"offset", "inf"}};
  for (const auto& [name, value] : bad) {
    const CliRun r = runEval(dir, "--gt '" + gtPath() + "' --est '" + gtPath() + "' --" + name + " " + value);
    EXPECT_EQ(r.status, 1) << name << " " << value << ": " << r.err;
    EXPECT_NE(r.err.find(std::string("--") + name + " must be"), std::string::npos) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
  }
}

TEST(evalCli, BadInputIsOneLineNamingTheFileAndExitTwo) {
  const auto dir = bmp::test::scratchDir("eval_cli_bad");
  const std::string bad = (dir / "bad.txt").string();
  test::writeText(bad, "1.0 0 0 0 0 0 0 1\n2.0 0 0 0 0 0 0\n");
  CliRun r = runEval(dir, "--gt '" + gtPath() + "' --est '" + bad + "'");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(lineCount(r.err), 1) << r.err;
  EXPECT_NE(r.err.find(bad + ":2"), std::string::npos) << r.err;

  const std::string missing = (dir / "missing.txt").string();
  r = runEval(dir, "--gt '" + missing + "' --est '" + gtPath() + "'");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(lineCount(r.err), 1) << r.err;
  EXPECT_NE(r.err.find(missing), std::string::npos) << r.err;

  const std::string far = (dir / "far.txt").string();
  test::writeText(far, "1.0 0 0 0 0 0 0 1\n2.0 1 0 0 0 0 0 1\n");
  r = runEval(dir, "--gt '" + gtPath() + "' --est '" + far + "'");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(lineCount(r.err), 1) << r.err;
  EXPECT_NE(r.err.find(far), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("no estimated stamp"), std::string::npos) << r.err;
}

}  // namespace bmp::eval

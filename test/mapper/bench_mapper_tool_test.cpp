// Runs the bmp-bench-mapper executable on the Bonn sequence: which poses place the keyframes, and what it
// says about them.
#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "run_command.hpp"
#include "shared_data.hpp"

namespace bmp {
namespace {

using ToolRun = test::Outcome;

// Two keyframes far apart on Bonn: enough to map, quick.
ToolRun benchMapper(const std::vector<std::string>& extra) {
  std::vector<std::string> arguments = {
      test::binPath("bmp-bench-mapper"), "--dataset", test::bonnDir(), "--every", "100", "--keyframes", "2"};
  arguments.insert(arguments.end(), extra.begin(), extra.end());
  return test::runCommand("bench_mapper", std::move(arguments), 120);
}

// Bonn's ground truth is its marker body's pose, about 176 degrees off the camera (README): a map built on
// it is smeared, which the benchmark once did without a word. It says so, and takes camera poses instead.
TEST(BenchMapperTool, BonnsGroundTruthIsWarnedAboutAndCameraPosesCanBeGiven) {
  const ToolRun truth = benchMapper({});
  ASSERT_EQ(truth.status, 0) << truth.output;
  EXPECT_NE(truth.output.find("marker body"), std::string::npos) << truth.output;
  EXPECT_NE(truth.output.find("--poses"), std::string::npos) << truth.output;

  // Any camera trajectory will do for the tool: here the first poses of the ground truth, as a file.
  const std::string poses = (test::scratchDir("poses") / "trajectory.txt").string();
  {
    std::ifstream in(test::bonnDir() + "/groundtruth.txt");
    std::ofstream out(poses);
    std::string line;
    for (int i = 0; i < 2000 && std::getline(in, line); ++i) out << line << "\n";
  }
  const ToolRun given = benchMapper({"--poses", poses});
  ASSERT_EQ(given.status, 0) << given.output;
  EXPECT_EQ(given.output.find("marker body"), std::string::npos) << given.output;
  EXPECT_NE(given.output.find("keyframes        2"), std::string::npos) << given.output;

  const ToolRun missing = benchMapper({"--poses", poses + ".missing"});
  EXPECT_NE(missing.status, 0) << missing.output;
  EXPECT_NE(missing.output.find(poses + ".missing"), std::string::npos) << missing.output;
}

// Counts below one (--every 0 divided by zero, --pixel-step 0 looped for ever) are usage errors naming the
// option, before the sequence is read.
TEST(BenchMapperTool, CountsOutOfRangeAreUsageErrors) {
  for (const char* option : {"--every", "--loops", "--keyframes", "--pixel-step"}) {
    const ToolRun r = benchMapper({option, "0"});
    EXPECT_EQ(r.status, 2) << option << ": " << r.output;
    EXPECT_NE(r.output.find(std::string(option) + " must be an integer from 1 to"), std::string::npos)
        << r.output;
  }
  const ToolRun step = benchMapper({"--pixel-step", "17"});
  EXPECT_EQ(step.status, 2) << step.output;
  EXPECT_NE(step.output.find("--pixel-step must be an integer from 1 to 16"), std::string::npos)
      << step.output;
}

}  // namespace
}  // namespace bmp

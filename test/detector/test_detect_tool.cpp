// Runs the bmp-detect executable: option values checked, what it says about the images it reads.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "bmp/common/child_process.hpp"
#include "shared_data.hpp"

namespace bmp {
namespace {

namespace fs = std::filesystem;

struct ToolRun {
  int status = -1;
  std::string output;  // stdout and stderr together
};

ToolRun detect(std::vector<std::string> arguments) {
  const std::string log = (test::scratchDir("detect_run") / "out.log").string();
  arguments.insert(arguments.begin(), test::binPath("bmp-detect"));
  ChildProcess child(std::move(arguments), ChildProcess::Output::kFile, log);
  ToolRun r;
  r.status = child.wait(120).value_or(-1);
  r.output = test::readText(log);
  return r;
}

// A confidence is a probability: --conf 5 found no box and --conf -1 every candidate, both without a word.
TEST(DetectTool, AConfidenceOutsideZeroToOneIsAUsageErrorNamingTheOption) {
  const std::string image = test::sharedPath("images/bus.jpg");
  for (const char* conf : {"5", "-1", "nan"}) {
    const ToolRun r = detect({"--input", image, "--conf", conf});
    EXPECT_EQ(r.status, 2) << conf << ": " << r.output;
    EXPECT_NE(r.output.find("--conf must be a number from 0 to 1"), std::string::npos) << r.output;
  }
  const ToolRun limit = detect({"--input", image, "--limit", "-1"});
  EXPECT_EQ(limit.status, 2) << limit.output;
  EXPECT_NE(limit.output.find("--limit"), std::string::npos) << limit.output;
}

}  // namespace
}  // namespace bmp

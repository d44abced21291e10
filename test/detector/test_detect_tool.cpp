// Runs the bmp-detect executable: option values checked, what it says about the images it reads.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "run_command.hpp"
#include "shared_data.hpp"

namespace bmp {
namespace {

namespace fs = std::filesystem;

using ToolRun = test::Outcome;

ToolRun detect(std::vector<std::string> arguments) {
  arguments.insert(arguments.begin(), test::binPath("bmp-detect"));
  return test::runCommand("detect_run", std::move(arguments), 120);
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

// A corrupt image in a folder stopped the run with a message naming no file: it is skipped with a warning
// naming it, the rest are read, and the end says how many were skipped.
TEST(DetectTool, ACorruptImageIsSkippedNamingItAndTheRestAreRead) {
  const fs::path dir = test::scratchDir("images");
  fs::copy_file(test::sharedPath("images/bus.jpg"), dir / "a.jpg");
  fs::copy_file(test::sharedPath("images/zidane.jpg"), dir / "c.jpg");
  {
    std::ifstream in(test::sharedPath("images/person.jpg"), std::ios::binary);
    std::string head(2000, '\0');
    in.read(head.data(), static_cast<std::streamsize>(head.size()));
    std::ofstream(dir / "b.jpg", std::ios::binary) << head;  // cut inside its headers
  }
  const ToolRun r = detect({"--input", dir.string()});
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("warning: " + (dir / "b.jpg").string() + ": "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("c: "), std::string::npos) << r.output;  // the image after it was read
  EXPECT_NE(r.output.find("1 of 3 image(s) skipped"), std::string::npos) << r.output;

  fs::remove(dir / "a.jpg");
  fs::remove(dir / "c.jpg");
  const ToolRun none = detect({"--input", dir.string()});
  EXPECT_EQ(none.status, 1) << none.output;
  EXPECT_NE(none.output.find(dir.string() + ": no image could be read"), std::string::npos) << none.output;
}

}  // namespace
}  // namespace bmp

// Runs the bmp-synth executable: option values are checked before anything is rendered or written.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "run_command.hpp"
#include "shared_data.hpp"

namespace bmp {
namespace {

// --frames -3 rendered an empty sequence without a word (the scene refused only negative counts, in its
// own words, after the folder was made).
TEST(SynthTool, AFrameCountBelowOneIsAUsageErrorAndNothingIsWritten) {
  const std::filesystem::path out = test::scratchDir("synth_tool") / "seq";
  for (const char* frames : {"-3", "0", "x"}) {
    const test::Outcome o =
        test::runCommand("synth", {test::binPath("bmp-synth"), "--frames", frames, "--out", out.string()});
    EXPECT_EQ(o.status, 2) << frames << ": " << o.output;
    EXPECT_NE(o.output.find("--frames must be an integer"), std::string::npos) << o.output;
    EXPECT_EQ(o.output.find("(see --help) (see --help)"), std::string::npos) << o.output;
    EXPECT_FALSE(std::filesystem::exists(out)) << frames;
  }
}

}  // namespace
}  // namespace bmp

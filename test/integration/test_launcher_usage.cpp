// bmp-run's options checked before anything starts: a bad one is a usage error (exit status 2) naming the
// option, with no process started and no run folder made.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "integration_support.hpp"

namespace bmp {
namespace {

namespace fs = std::filesystem;
using test::binPath;
using test::Outcome;
using test::runCommand;

TEST(LauncherUsage, BadOptionsAreRefusedBeforeAnythingStarts) {
  const fs::path dir = test::scratchDir("launcher_usage");
  std::ofstream(dir / "run.yaml") << "run:\n  output_root: " << (dir / "root").string()
                                  << "\n  processes:\n    bmp-test-listener: [--ack]\n  capture_args: []\n";
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"--mode", "bogus"}, "--mode 'bogus'"},
      {{"--speed", "abc"}, "--speed must be a number"},
      {{"--speed", "0"}, "--speed must be a number above 0, got '0'"},
      {{"--speed", "-1"}, "--speed must be a number above 0, got '-1'"},
      {{"--loop", "0"}, "--loop must be an integer from 1 to 1000000, got '0'"},
      {{"--frames", "-5"}, "--frames must be an integer from 1 to 100000000, got '-5'"},
      {{"--frames", "0"}, "--frames must be an integer from 1 to 100000000, got '0'"},
      {{"--camera", "/nonexist.yaml"}, "--camera '/nonexist.yaml'"},
      {{"--dataset", "/nonexist/seq"}, "--dataset '/nonexist/seq'"}};
  for (const auto& [bad, message] : cases) {
    // Once with --out, once without (the folder and the latest link bmp-run would make under output_root).
    for (const bool with_out : {true, false}) {
      std::vector<std::string> argv = {binPath("bmp-run"), "--config", (dir / "run.yaml").string(),
                                       "--lcm-url", "memq://"};
      if (with_out) argv.insert(argv.end(), {"--out", (dir / "run").string()});
      argv.insert(argv.end(), bad.begin(), bad.end());
      const Outcome o = runCommand("launcher_usage", argv, 60);
      EXPECT_EQ(o.status, 2) << bad[0] << " " << bad[1] << ": " << o.output;
      EXPECT_NE(o.output.find(message), std::string::npos) << o.output;
      EXPECT_EQ(o.output.find("started "), std::string::npos) << o.output;
      EXPECT_FALSE(fs::exists(dir / "run")) << bad[0] << " " << bad[1];
      EXPECT_FALSE(fs::exists(dir / "root")) << bad[0] << " " << bad[1];
    }
  }
}

}  // namespace
}  // namespace bmp

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
      {{"--speed", "0"}, "--speed must be a number from 0.001 to 1000, got '0'"},
      {{"--speed", "-1"}, "--speed must be a number from 0.001 to 1000, got '-1'"},
      {{"--speed", "1e-300"}, "--speed must be a number from 0.001 to 1000, got '1e-300'"},
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

// A dataset capture would refuse at start-up (no lists, a malformed line, a broken camera file), or a
// process in run.yaml that is not built: refused before the run folder is touched. Each once set the earlier
// run in --out aside into previous/ and left an empty one in its place, so a second such attempt lost it.
TEST(LauncherUsage, ADatasetCaptureWouldRefuseLeavesTheEarlierRunInOutAsItWas) {
  const fs::path dir = test::scratchDir("launcher_earlier_run");
  std::ofstream(dir / "run.yaml") << "run:\n  output_root: " << (dir / "root").string()
                                  << "\n  processes:\n    bmp-test-listener: [--ack]\n  capture_args: []\n";
  std::ofstream(dir / "misspelt.yaml") << "run:\n  output_root: " << (dir / "root").string()
                                       << "\n  processes:\n    bmp-trakcer: []\n  capture_args: []\n";
  fs::create_directories(dir / "run" / "logs");
  std::ofstream(dir / "run" / "eval.json") << "{\"ate_rmse_m\": 0.0108}\n";
  fs::create_directories(dir / "empty");
  fs::create_directories(dir / "malformed");
  std::ofstream(dir / "malformed" / "rgb.txt") << "1305031102.175304 rgb/1.png\nnot a line\n";
  std::ofstream(dir / "malformed" / "depth.txt") << "1305031102.160407 depth/1.png\n";
  std::ofstream(dir / "camera.yaml") << "camera: {width: 640}\n";
  const std::string bonn = test::bonnDir();
  const std::string run_yaml = (dir / "run.yaml").string();
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"--config", run_yaml, "--dataset", (dir / "empty").string()}, "rgb.txt is missing"},
      {{"--config", run_yaml, "--dataset", (dir / "malformed").string()}, "malformed/rgb.txt:2: "},
      {{"--config", run_yaml, "--dataset", bonn, "--camera", (dir / "camera.yaml").string()},
       "camera.yaml: required key 'camera.height' is missing"},
      {{"--config", run_yaml, "--dataset", (dir / "run.yaml").string()}, "not a folder"},
      {{"--config", (dir / "misspelt.yaml").string(), "--dataset", bonn}, "bmp-trakcer: not built"}};
  for (const auto& [bad, message] : cases) {
    std::vector<std::string> argv = {binPath("bmp-run"), "--lcm-url", "memq://", "--out",
                                     (dir / "run").string()};
    argv.insert(argv.end(), bad.begin(), bad.end());
    const Outcome o = runCommand("launcher_earlier_run", argv, 60);
    EXPECT_NE(o.status, 0) << message << ": " << o.output;
    EXPECT_NE(o.output.find(message), std::string::npos) << o.output;
    EXPECT_EQ(o.output.find("started "), std::string::npos) << o.output;
    EXPECT_EQ(test::readText((dir / "run" / "eval.json").string()), "{\"ate_rmse_m\": 0.0108}\n") << message;
    EXPECT_FALSE(fs::exists(dir / "run" / "previous")) << message;
  }
  // LCM that cannot be opened: the run set the earlier one aside first, and a second attempt lost it.
  for (int attempt = 0; attempt < 2; ++attempt) {
    const Outcome o = runCommand("launcher_earlier_run",
                                 {binPath("bmp-run"), "--lcm-url", "foo://bar", "--out",
                                  (dir / "run").string(), "--config", run_yaml, "--dataset", bonn},
                                 60);
    EXPECT_NE(o.status, 0) << o.output;
    EXPECT_NE(o.output.find("cannot open LCM at 'foo://bar'"), std::string::npos) << o.output;
    EXPECT_EQ(test::readText((dir / "run" / "eval.json").string()), "{\"ate_rmse_m\": 0.0108}\n");
    EXPECT_FALSE(fs::exists(dir / "run" / "previous"));
  }
}

// An --out that cannot be made is a usage error naming it, not a filesystem exception.
TEST(LauncherUsage, AnOutFolderThatCannotBeMadeIsAUsageError) {
  const fs::path dir = test::scratchDir("launcher_out_unmakeable");
  std::ofstream(dir / "file") << "a file, not a folder\n";
  const std::string out = (dir / "file" / "run").string();
  const Outcome o =
      runCommand("launcher_out_unmakeable",
                 {binPath("bmp-run"), "--lcm-url", "memq://", "--out", out, "--frames", "5"}, 60);
  EXPECT_EQ(o.status, 2) << o.output;
  EXPECT_NE(o.output.find("--out '" + out + "': cannot make the folder: Not a directory"), std::string::npos)
      << o.output;
  EXPECT_EQ(o.output.find("started "), std::string::npos) << o.output;
}

}  // namespace
}  // namespace bmp

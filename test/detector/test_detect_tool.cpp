// Runs the bmp-detect and bmp-bench-detector executables: option values checked, what they say about the
// images they read.
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

// A scratch folder of three photos, the middle one (b.jpg) cut off inside its JPEG headers.
fs::path folderWithACorruptImage(const std::string& name) {
  const fs::path dir = test::scratchDir(name);
  fs::copy_file(test::sharedPath("images/bus.jpg"), dir / "a.jpg");
  fs::copy_file(test::sharedPath("images/zidane.jpg"), dir / "c.jpg");
  std::ifstream in(test::sharedPath("images/person.jpg"), std::ios::binary);
  std::string head(2000, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  std::ofstream(dir / "b.jpg", std::ios::binary) << head;
  return dir;
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

// The darknet model reports no score under 0.2 (OpenCV's region layer drops them): a lower threshold is
// said to find nothing more (--conf 0.05 looked like it worked). The ONNX models have no such floor.
TEST(DetectTool, ADarknetThresholdUnderItsFloorIsWarnedAbout) {
  const ToolRun r = detect(
      {"--input", test::sharedPath("images/messi5.jpg"), "--model", "yolo-fastest-xl", "--conf", "0.05"});
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(
      r.output.find("conf_threshold 0.05 is below 0.2, under which OpenCV's darknet layer reports no score"),
      std::string::npos)
      << r.output;
  const ToolRun onnx = detect({"--input", test::sharedPath("images/messi5.jpg"), "--conf", "0.05"});
  EXPECT_EQ(onnx.output.find("is below 0.2"), std::string::npos) << onnx.output;
}

// A corrupt image in a folder stopped the run with a message naming no file: it is skipped with a warning
// naming it, the rest are read, and the end says how many were skipped.
TEST(DetectTool, ACorruptImageIsSkippedNamingItAndTheRestAreRead) {
  const fs::path dir = folderWithACorruptImage("images");
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

ToolRun bench(std::vector<std::string> arguments) {
  arguments.insert(arguments.begin(), test::binPath("bmp-bench-detector"));
  return test::runCommand("bench_detector_run", std::move(arguments), 120);
}

// bmp-bench-detector: --frames 0 ended in a floating-point exception, -1 quietly meant every frame, and an
// unknown model was found only after the table's header. Each is now a usage error naming the option.
TEST(BenchDetectorTool, CountsAndModelsOutsideTheirRangeAreUsageErrors) {
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"--frames", "0"}, "--frames must be an integer from 1 to 1000000, got '0'"},
      {{"--frames", "-1"}, "--frames must be an integer from 1 to 1000000, got '-1'"},
      {{"--warmup", "-1"}, "--warmup must be an integer from 0 to 1000000, got '-1'"},
      {{"--threads", "0"}, "--threads must be an integer from 1 to 256, got '0'"},
      {{"--models", ""}, "--models names no model"},
      {{"--models", "yolov5n-320,bogus"}, "--models: unknown model 'bogus'"}};
  for (const auto& [arguments, message] : cases) {
    const ToolRun r = bench(arguments);
    EXPECT_EQ(r.status, 2) << arguments[0] << " " << arguments[1] << ": " << r.output;
    EXPECT_NE(r.output.find(message), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("median_ms"), std::string::npos) << r.output;  // no table started
  }
}

// A corrupt image among those timed stopped the benchmark with a message naming no file: it is left out,
// named, and the rest are timed.
TEST(BenchDetectorTool, ACorruptImageIsLeftOutNamingItAndTheRestAreTimed) {
  const fs::path dir = folderWithACorruptImage("bench_images");
  const ToolRun r =
      bench({"--input", dir.string(), "--frames", "3", "--warmup", "0", "--models", "yolov5n-320"});
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find((dir / "b.jpg").string() + ": JPEG truncated"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("2 frames of " + dir.string()), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("yolov5n_coco_320              320     2 "), std::string::npos) << r.output;
}

}  // namespace
}  // namespace bmp

#include "detect_run.hpp"

#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <optional>

#include <opencv2/imgcodecs.hpp>

#include "annotate.hpp"
#include "bmp/common/arg_range.hpp"
#include "bmp/common/config.hpp"
#include "bmp/common/image_codec.hpp"
#include "detector/detection_worker.hpp"
#include "image_list.hpp"

namespace fs = std::filesystem;

namespace bmp::detect_tools {

namespace {

using namespace bmp::detector;

DetectorConfig loadConfig(const ArgParser& args, std::string& dynamic_path) {
  const std::string path = args.value("config");
  const Config config = Config::fromFile(path);
  DetectorConfig c = detectorConfigFromYaml(config);
  dynamic_path = config.get<std::string>("dynamic_classes", "dynamic_classes.yaml");
  if (!fs::path(dynamic_path).is_absolute())
    dynamic_path = (fs::path(path).parent_path() / dynamic_path).string();
  // The process's own sections are not this tool's business; anything else unknown is a typo.
  config.ignore("process");
  config.ignore("channels");
  config.finish();
  if (args.given("dynamic-classes")) dynamic_path = args.value("dynamic-classes");
  if (args.given("model")) c = withModelPreset(c, args.value("model"));
  // A confidence is a probability: above 1 no box passes, below 0 every candidate does.
  if (args.given("conf")) c.conf_threshold = static_cast<float>(numberIn(args, "conf", 0.0, 1.0));
  if (args.given("threads"))
    c.threads = static_cast<int>(integerIn(args, "threads", 1, std::numeric_limits<int>::max()));
  return c;
}

void printDetections(const ImageEntry& image, const FrameResult& result) {
  std::cout << image.name << ": " << result.detections.size() << " detection(s), " << result.total_ms
            << " ms\n";
  for (const auto& d : result.detections)
    std::cout << "  " << d.label << " " << d.score << " " << toString(d.level) << " [" << d.box.x << ", "
              << d.box.y << ", " << d.box.width << ", " << d.box.height << "]\n";
}

// --out: the annotated image, and the JSON line into detections.jsonl or a file of its own.
void writeOutputs(const fs::path& out_dir, const ImageEntry& image, const EncodedImage& encoded,
                  const FrameResult& result, const std::string& json, std::optional<std::ofstream>& jsonl) {
  cv::Mat bgr = decodeImage(encoded);
  drawDetections(bgr, result.detections);
  const fs::path png = out_dir / (image.name + ".png");
  if (!cv::imwrite(png.string(), bgr)) throw std::runtime_error(png.string() + ": cannot write");
  if (jsonl) {
    *jsonl << json << "\n";
  } else {
    std::ofstream(out_dir / (image.name + ".json")) << json << "\n";
  }
}

}  // namespace

int runDetect(const ArgParser& args) {
  if (!args.given("input")) throw ArgError("bmp-detect: --input is required");
  std::string dynamic_path;
  const DetectorConfig config = loadConfig(args, dynamic_path);
  Detector detector(config, Config::fromFile(dynamic_path));
  const auto images = listImages(args.value("input"));
  const long long limit =
      args.given("limit") ? integerIn(args, "limit", 1, std::numeric_limits<long long>::max()) : 0;

  const std::string out_dir = args.value("out");
  std::optional<std::ofstream> jsonl;
  if (!out_dir.empty()) {
    fs::create_directories(out_dir);
    if (args.flag("jsonl")) jsonl.emplace(fs::path(out_dir) / "detections.jsonl");
  }
  std::cerr << "model " << detector.modelName() << ", " << images.size() << " image(s)\n";
  long long done = 0, skipped = 0;
  for (const auto& image : images) {
    if (limit > 0 && done >= limit) break;
    ++done;
    // A file that cannot be read or decoded is skipped and named, as bmp-capture skips bad files.
    FrameJob job;
    try {
      job = loadFrameJob(image.path);
    } catch (const ImageError& e) {
      std::cerr << "warning: " << image.path << ": " << e.what() << "; skipped\n";
      ++skipped;
      continue;
    }
    const FrameResult result = processFrame(detector, job);
    if (!result.ok) {
      std::cerr << "warning: " << image.path << ": " << result.error << "; skipped\n";
      ++skipped;
      continue;
    }
    const std::string json = detectionsJson(image.path, image.stamp, detector.modelName(), result.width,
                                            result.height, result.total_ms, result.detections);
    printDetections(image, result);
    if (!out_dir.empty()) writeOutputs(out_dir, image, job.color, result, json, jsonl);
  }
  if (skipped > 0) std::cerr << skipped << " of " << done << " image(s) skipped (each named above)\n";
  // As bmp-capture, which exits 1 when it published nothing: no image read is no result.
  if (done > 0 && skipped == done) throw std::runtime_error(args.value("input") + ": no image could be read");
  return 0;
}

}  // namespace bmp::detect_tools

// bmp-detect: run the detector on an image, a folder or a TUM sequence and write what it sees.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>

#include <opencv2/imgcodecs.hpp>

#include "annotate.hpp"
#include "bmp/common/arg_parser.hpp"
#include "bmp/common/config.hpp"
#include "bmp/common/image_codec.hpp"
#include "bmp/common/tool_main.hpp"
#include "detector/detection_worker.hpp"
#include "image_list.hpp"

namespace fs = std::filesystem;
using namespace bmp::detector;

namespace {

std::string defaultConfigDir() {
  if (const char* env = std::getenv("BMP_CONFIG_DIR"); env != nullptr && *env != '\0') return env;
  return BMP_SOURCE_CONFIG_DIR;
}

DetectorConfig loadConfig(const bmp::ArgParser& args, std::string& dynamic_path) {
  const std::string path = args.value("config");
  const bmp::Config config = bmp::Config::fromFile(path);
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
  if (args.given("conf")) c.conf_threshold = static_cast<float>(args.number("conf"));
  if (args.given("threads")) c.threads = static_cast<int>(args.integer("threads"));
  return c;
}

int run(const bmp::ArgParser& args) {
  std::string dynamic_path;
  const DetectorConfig config = loadConfig(args, dynamic_path);
  Detector detector(config, bmp::Config::fromFile(dynamic_path));
  const auto images = bmp::detect_tools::listImages(args.value("input"));
  const long long limit = args.given("limit") ? args.integer("limit") : 0;

  const std::string out_dir = args.value("out");
  std::optional<std::ofstream> jsonl;
  if (!out_dir.empty()) {
    fs::create_directories(out_dir);
    if (args.flag("jsonl")) jsonl.emplace(fs::path(out_dir) / "detections.jsonl");
  }
  std::cerr << "model " << detector.modelName() << ", " << images.size() << " image(s)\n";
  long long done = 0;
  for (const auto& image : images) {
    if (limit > 0 && done >= limit) break;
    FrameJob job;
    bmp::EncodedImage& encoded = job.color;
    encoded.data = bmp::readFileBytes(image.path);
    const bmp::ImageProbe probe = bmp::probeEncodedImage(encoded.data);
    encoded.width = probe.width;
    encoded.height = probe.height;
    encoded.encoding = probe.encoding;
    const FrameResult result = processFrame(detector, job);
    ++done;
    if (!result.ok) {
      std::cerr << image.path << ": " << result.error << "; skipped\n";
      continue;
    }
    const std::string json =
        bmp::detect_tools::detectionsJson(image.path, image.stamp, detector.modelName(), result.width,
                                          result.height, result.total_ms, result.detections);
    std::cout << image.name << ": " << result.detections.size() << " detection(s), " << result.total_ms
              << " ms\n";
    for (const auto& d : result.detections)
      std::cout << "  " << d.label << " " << d.score << " " << toString(d.level) << " [" << d.box.x << ", "
                << d.box.y << ", " << d.box.width << ", " << d.box.height << "]\n";
    if (out_dir.empty()) continue;
    cv::Mat bgr = bmp::decodeImage(encoded);
    bmp::detect_tools::drawDetections(bgr, result.detections);
    const fs::path png = fs::path(out_dir) / (image.name + ".png");
    if (!cv::imwrite(png.string(), bgr)) throw std::runtime_error(png.string() + ": cannot write");
    if (jsonl) {
      *jsonl << json << "\n";
    } else {
      std::ofstream(fs::path(out_dir) / (image.name + ".json")) << json << "\n";
    }
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  bmp::ArgParser args(
      "bmp-detect",
      "Runs the detector on one image, every PNG/JPEG of a folder, or the colour frames of a "
      "TUM sequence folder (rgb.txt), prints the boxes and, with --out, writes annotated PNGs "
      "(high-dynamic red, medium orange, low green) and JSON.");
  args.addOption("input", "PATH", "image file, image folder, or TUM sequence folder");
  args.addOption("out", "DIR", "write <name>.png (annotated) and <name>.json per image here");
  args.addFlag("jsonl", "with --out: one detections.jsonl instead of a JSON file per image");
  args.addOption("config", "FILE", "detector configuration", defaultConfigDir() + "/detector.yaml");
  args.addOption("dynamic-classes", "FILE", "dynamic levels; default: dynamic_classes of the configuration");
  args.addOption("model", "NAME",
                 "yolov5n-320, yolov5n-640 or yolo-fastest-xl instead of the configured model");
  args.addOption("conf", "X", "confidence threshold instead of the configured one");
  args.addOption("threads", "N", "OpenCV threads instead of the configured number");
  args.addOption("limit", "N", "stop after N images");
  return bmp::runTool(args, argc, argv, [](const bmp::ArgParser& parsed) {
    if (!parsed.given("input")) throw bmp::ArgError("bmp-detect: --input is required");
    return run(parsed);
  });
}

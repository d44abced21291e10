// bmp-bench-detector: median and p95 of the detector's per-frame time for each model and input size.
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <sstream>

#include "bmp/common/arg_parser.hpp"
#include "bmp/common/config.hpp"
#include "bmp/common/timing.hpp"
#include "bmp/common/tool_main.hpp"
#include "detector/detection_worker.hpp"
#include "detector/shared_paths.hpp"
#include "image_list.hpp"

using namespace bmp::detector;

namespace {

constexpr double kTargetMs = 30.0;  // YOLOv5n at 320 should keep up with a 30 Hz camera

std::string configDir() {
  if (const char* env = std::getenv("BMP_CONFIG_DIR"); env != nullptr && *env != '\0') return env;
  return BMP_SOURCE_CONFIG_DIR;
}

std::vector<std::string> splitCommas(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string item; std::getline(in, item, ',');)
    if (!item.empty()) out.push_back(item);
  return out;
}

// n frames spread evenly over the sequence, read into memory so disk time is not measured.
std::vector<FrameJob> loadFrames(const std::string& input, long long n) {
  const auto images = bmp::detect_tools::listImages(input);
  const std::size_t count = std::min<std::size_t>(images.size(), static_cast<std::size_t>(n));
  std::vector<FrameJob> jobs;
  for (std::size_t i = 0; i < count; ++i) {
    const auto& image = images[i * images.size() / count];
    FrameJob job;
    job.seq = static_cast<int64_t>(i);
    job.color.data = bmp::readFileBytes(image.path);
    const bmp::ImageProbe probe = bmp::probeEncodedImage(job.color.data);
    job.color.width = probe.width;
    job.color.height = probe.height;
    job.color.encoding = probe.encoding;
    jobs.push_back(std::move(job));
  }
  return jobs;
}

int run(const bmp::ArgParser& args) {
  const bmp::Config file = bmp::Config::fromFile(args.value("config"));
  DetectorConfig base = detectorConfigFromYaml(file);
  if (args.given("threads")) base.threads = static_cast<int>(args.integer("threads"));
  const bmp::Config dynamic = bmp::Config::fromFile(configDir() + "/dynamic_classes.yaml");
  const auto frames = loadFrames(args.value("input"), args.integer("frames"));
  const long long warmup = args.integer("warmup");
  std::printf("%zu frames of %s, %d OpenCV thread(s), %lld warm-up frame(s) per model\n", frames.size(),
              args.value("input").c_str(), base.threads, warmup);
  std::printf("%-26s %6s %5s %10s %10s %10s %14s\n", "model", "input", "n", "median_ms", "p95_ms", "mean_ms",
              "median/30ms");
  for (const auto& preset : splitCommas(args.value("models"))) {
    Detector detector(withModelPreset(base, preset), dynamic);
    for (long long i = 0; i < warmup; ++i) processFrame(detector, frames[i % frames.size()]);
    bmp::TimingStats stats, decode, letterbox, inference, nms;
    for (const auto& job : frames) {
      const FrameResult result = processFrame(detector, job);
      if (!result.ok) throw std::runtime_error("frame " + std::to_string(job.seq) + ": " + result.error);
      stats.add(result.total_ms);
      decode.add(result.stages.decode_ms);
      letterbox.add(result.stages.letterbox_ms);
      inference.add(result.stages.inference_ms);
      nms.add(result.stages.nms_ms);
    }
    std::printf("%-26s %6d %5zu %10.1f %10.1f %10.1f %14.2f\n", detector.modelName().c_str(),
                detector.config().input_size, stats.count(), stats.median(), stats.p95(), stats.mean(),
                stats.median() / kTargetMs);
    std::printf("  stage medians: decode %.1f, letterbox %.1f, inference %.1f, nms %.1f ms\n",
                decode.median(), letterbox.median(), inference.median(), nms.median());
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  bmp::ArgParser args("bmp-bench-detector",
                      "Times the detector per frame (decode + letterbox + inference + NMS) for each model on "
                      "real frames, and prints median, p95 and the ratio of the median to the 30 ms target. "
                      "Run it on an otherwise idle machine, from a Release build.");
  args.addOption("input", "PATH", "TUM sequence folder, image folder or image",
                 resolveSharedPath("data/rgbd_bonn_crowd"));
  args.addOption("frames", "N", "frames to time per model, spread over the input", "100");
  args.addOption("warmup", "N", "untimed frames first", "5");
  args.addOption("models", "LIST", "comma-separated: yolov5n-320, yolov5n-640, yolo-fastest-xl",
                 "yolov5n-320,yolov5n-640,yolo-fastest-xl");
  args.addOption("threads", "N", "OpenCV threads instead of the configured number");
  args.addOption("config", "FILE", "detector configuration (thresholds, threads)",
                 configDir() + "/detector.yaml");
  return bmp::runTool(args, argc, argv, run);
}

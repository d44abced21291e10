#include "detector_bench.hpp"

#include <algorithm>
#include <cstdio>
#include <stdexcept>

#include "bmp/common/arg_range.hpp"
#include "bmp/common/config.hpp"
#include "bmp/common/config_dir.hpp"
#include "bmp/common/image_codec.hpp"
#include "bmp/common/log.hpp"
#include "bmp/common/timing.hpp"
#include "detector/detection_worker.hpp"
#include "image_list.hpp"

namespace bmp::detect_tools {

namespace {

using namespace bmp::detector;

constexpr double kTargetMs = 30.0;  // YOLOv5n at 320 should keep up with a 30 Hz camera
constexpr long long kMaxCount = 1000000, kMaxThreads = 256;

// n frames spread evenly over the sequence, read into memory so disk time is not measured. An image that
// cannot be read or decoded is left out, named, as the detector would skip it: it has no time to measure.
std::vector<FrameJob> loadFrames(const std::string& input, long long n) {
  const auto images = listImages(input);
  const std::size_t count = std::min<std::size_t>(images.size(), static_cast<std::size_t>(n));
  std::vector<FrameJob> jobs;
  for (std::size_t i = 0; i < count; ++i) {
    const std::string& path = images[i * images.size() / count].path;
    try {
      FrameJob job = loadFrameJob(path, static_cast<int64_t>(jobs.size()));
      decodeImage(job.color);
      jobs.push_back(std::move(job));
    } catch (const std::exception& e) {
      log::warn(path, ": ", e.what(), "; left out");
    }
  }
  if (jobs.empty())
    throw std::runtime_error(input + ": no readable image among the " + std::to_string(count));
  return jobs;
}

// Times every frame once after the warm-up and prints the model's row and its stage medians.
void benchModel(Detector& detector, const std::vector<FrameJob>& frames, long long warmup) {
  for (long long i = 0; i < warmup; ++i) processFrame(detector, frames[i % frames.size()]);
  TimingStats stats, decode, letterbox, inference, nms;
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
  std::printf("  stage medians: decode %.1f, letterbox %.1f, inference %.1f, nms %.1f ms\n", decode.median(),
              letterbox.median(), inference.median(), nms.median());
}

}  // namespace

int runDetectorBenchmark(const ArgParser& args) {
  const Config file = Config::fromFile(args.value("config"));
  DetectorConfig base = detectorConfigFromYaml(file);
  if (args.given("threads")) base.threads = static_cast<int>(integerIn(args, "threads", 1, kMaxThreads));
  const long long n = integerIn(args, "frames", 1, kMaxCount);
  const long long warmup = integerIn(args, "warmup", 0, kMaxCount);
  // Every model named before any is timed: a misspelt one must not end the run half way.
  std::vector<DetectorConfig> models;
  for (const auto& preset : args.list("models")) {
    try {
      models.push_back(withModelPreset(base, preset));
    } catch (const std::invalid_argument& e) {
      throw ArgError("bmp-bench-detector: --models: " + std::string(e.what()));
    }
  }
  if (models.empty()) throw ArgError("bmp-bench-detector: --models names no model");
  const Config dynamic = Config::fromFile(configDir() + "/dynamic_classes.yaml");
  const auto frames = loadFrames(args.value("input"), n);
  std::printf("%zu frames of %s, %d OpenCV thread(s), %lld warm-up frame(s) per model\n", frames.size(),
              args.value("input").c_str(), base.threads, warmup);
  std::printf("%-26s %6s %5s %10s %10s %10s %14s\n", "model", "input", "n", "median_ms", "p95_ms", "mean_ms",
              "median/30ms");
  for (const DetectorConfig& model : models) {
    Detector detector(model, dynamic);
    benchModel(detector, frames, warmup);
  }
  return 0;
}

}  // namespace bmp::detect_tools

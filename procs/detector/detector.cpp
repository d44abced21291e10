#include "detector/detector.hpp"

#include <opencv2/core/utility.hpp>

#include "bmp/common/log.hpp"
#include "bmp/common/timing.hpp"
#include "detector/letterbox.hpp"

namespace bmp::detector {

namespace {
ModelSpec withThreads(const DetectorConfig& config) {
  // Before the model's test inference, so that one already runs with the configured threads.
  cv::setNumThreads(config.threads);
  return config.modelSpec();
}
}  // namespace

// OpenCV's darknet region layer zeroes class scores under its own threshold: a lower one finds nothing more.
constexpr float kDarknetScoreFloor = 0.2f;

Detector::Detector(const DetectorConfig& config, const Config& dynamic_classes)
    : config_(config),
      model_(withThreads(config)),
      levels_(DynamicClassTable::fromConfig(dynamic_classes, model_.classNames())) {
  if (config_.modelSpec().kind == ModelKind::kDarknet && config_.conf_threshold < kDarknetScoreFloor)
    log::warn("conf_threshold ", config_.conf_threshold, " is below ", kDarknetScoreFloor,
              ", under which OpenCV's darknet layer reports no score: this model finds nothing under ",
              kDarknetScoreFloor);
}

std::vector<Detection> Detector::detect(const cv::Mat& bgr, StageTimes* times) {
  Stopwatch watch;
  const LetterboxTransform transform = letterbox(bgr, model_.inputSize(), square_);
  const double letterbox_ms = watch.elapsedMs();
  watch.restart();
  const cv::Mat rows = model_.infer(square_);
  const double inference_ms = watch.elapsedMs();
  watch.restart();
  const auto kept =
      nmsPerClass(model_.decode(rows, config_.conf_threshold), config_.nms_threshold, config_.max_detections);
  const cv::Rect2f image_rect(0, 0, static_cast<float>(bgr.cols), static_cast<float>(bgr.rows));
  std::vector<Detection> detections;
  detections.reserve(kept.size());
  for (const auto& c : kept) {
    const cv::Rect2f box = transform.toImage(c.box) & image_rect;
    if (box.area() <= 0.0f) continue;
    const std::string& label = model_.classNames()[c.class_id];
    detections.push_back({box, c.class_id, label, c.score, levels_.levelOf(label)});
  }
  if (times != nullptr) {
    times->letterbox_ms = letterbox_ms;
    times->inference_ms = inference_ms;
    times->nms_ms = watch.elapsedMs();
  }
  return detections;
}

}  // namespace bmp::detector

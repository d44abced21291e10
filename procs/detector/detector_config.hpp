#pragma once
// Every tunable of the detector, with its default. The process fills it from config/detector.yaml.
#include <string>
#include <vector>

#include "bmp/common/config.hpp"
#include "detector/yolo_model.hpp"

namespace bmp::detector {

// The most boxes one frame's answer may carry: DETECTIONS' MAX_DETECTIONS (checked where both are seen).
inline constexpr int kMaxDetectionsPerFrame = 300;

struct DetectorConfig {
  ModelKind kind = ModelKind::kOnnx;
  // Paths relative to the shared folder (see shared_paths.hpp) or absolute.
  std::string model_path = "models/yolov5n/yolov5n_coco_320.onnx";
  std::string darknet_cfg = "models/yolo-fastest/yolo-fastest-1.1-xl.cfg";
  std::string class_names = "models/coco.names";
  int input_size = 320;
  float conf_threshold = 0.25f;  // objectness x class probability
  float nms_threshold = 0.45f;   // IoU above which a lower-scored box of the same class is dropped
  int max_detections = 100;      // at most kMaxDetectionsPerFrame
  int threads = 2;               // OpenCV's worker threads (process-wide in OpenCV)

  // The model files, resolved against the shared folder.
  ModelSpec modelSpec() const;
};

// Reads section "model" (kind, path, darknet_cfg, names, input_size) and section "detection"
// (conf_threshold, nms_threshold, max_detections, threads) of config; absent keys keep their defaults.
// Throws ConfigError naming the file and key for a wrong type or an out-of-range value.
DetectorConfig detectorConfigFromYaml(const Config& config);

// The models in the shared folder by name, for tools that switch between them: "yolov5n-320",
// "yolov5n-640", "yolo-fastest-xl". Sets kind, paths and input size of base; throws std::invalid_argument
// listing the names for any other.
DetectorConfig withModelPreset(DetectorConfig base, const std::string& preset);
const std::vector<std::string>& modelPresets();

}  // namespace bmp::detector

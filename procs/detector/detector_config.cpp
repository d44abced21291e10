#include "detector/detector_config.hpp"

#include <stdexcept>

#include "detector/shared_paths.hpp"

namespace bmp::detector {

ModelSpec DetectorConfig::modelSpec() const {
  ModelSpec spec;
  spec.kind = kind;
  spec.path = resolveSharedPath(model_path);
  spec.darknet_cfg = kind == ModelKind::kDarknet ? resolveSharedPath(darknet_cfg) : "";
  spec.names = resolveSharedPath(class_names);
  spec.input_size = input_size;
  return spec;
}

DetectorConfig detectorConfigFromYaml(const Config& config) {
  DetectorConfig c;
  const Config model = config.section("model");
  const std::string kind = model.get<std::string>("kind", toString(c.kind));
  try {
    c.kind = parseModelKind(kind);
  } catch (const std::invalid_argument& e) {
    throw ConfigError(model.origin() + ": key '" + model.path("kind") + "': " + e.what());
  }
  c.model_path = model.get<std::string>("path", c.model_path);
  c.darknet_cfg = model.get<std::string>("darknet_cfg", c.darknet_cfg);
  c.class_names = model.get<std::string>("names", c.class_names);
  c.input_size = model.get<int>("input_size", c.input_size);
  model.check(c.input_size >= 32 && c.input_size % 32 == 0, "input_size",
              "must be a positive multiple of 32");

  const Config detection = config.section("detection");
  c.conf_threshold = static_cast<float>(detection.get<double>("conf_threshold", c.conf_threshold));
  detection.check(c.conf_threshold > 0 && c.conf_threshold < 1, "conf_threshold", "must be in (0, 1)");
  c.nms_threshold = static_cast<float>(detection.get<double>("nms_threshold", c.nms_threshold));
  detection.check(c.nms_threshold > 0 && c.nms_threshold <= 1, "nms_threshold", "must be in (0, 1]");
  c.max_detections = detection.get<int>("max_detections", c.max_detections);
  detection.check(
      c.max_detections > 0 && c.max_detections <= kMaxDetectionsPerFrame, "max_detections",
      "must be in [1, " + std::to_string(kMaxDetectionsPerFrame) + "], the most DETECTIONS carries");
  c.threads = detection.get<int>("threads", c.threads);
  detection.check(c.threads > 0, "threads", "must be positive");
  return c;
}

const std::vector<std::string>& modelPresets() {
  static const std::vector<std::string> names{"yolov5n-320", "yolov5n-640", "yolo-fastest-xl"};
  return names;
}

DetectorConfig withModelPreset(DetectorConfig base, const std::string& preset) {
  if (preset == "yolov5n-320" || preset == "yolov5n-640") {
    base.kind = ModelKind::kOnnx;
    base.input_size = preset == "yolov5n-320" ? 320 : 640;
    base.model_path = "models/yolov5n/yolov5n_coco_" + std::to_string(base.input_size) + ".onnx";
  } else if (preset == "yolo-fastest-xl") {
    base.kind = ModelKind::kDarknet;
    base.input_size = 320;
    base.model_path = "models/yolo-fastest/yolo-fastest-1.1-xl.weights";
    base.darknet_cfg = "models/yolo-fastest/yolo-fastest-1.1-xl.cfg";
  } else {
    std::string known;
    for (const auto& name : modelPresets()) known += (known.empty() ? "" : ", ") + name;
    throw std::invalid_argument("unknown model '" + preset + "' (known: " + known + ")");
  }
  return base;
}

}  // namespace bmp::detector

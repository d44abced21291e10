#pragma once
// The detection stage: one colour image in, boxes with class, score and dynamic level out.
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "detector/detector_config.hpp"
#include "detector/dynamic_classes.hpp"
#include "detector/yolo_model.hpp"

namespace bmp::detector {

struct Detection {
  cv::Rect2f box;  // original image pixels, clipped to the image
  int class_id = 0;
  std::string label;
  float score = 0.0f;
  DynamicLevel level = DynamicLevel::kLow;
};

// Where the time of one detect() call went, milliseconds.
struct StageTimes {
  double decode_ms = 0.0;  // filled by processFrame
  double letterbox_ms = 0.0;
  double inference_ms = 0.0;
  double nms_ms = 0.0;  // decode of the output rows + NMS + mapping back
};

class Detector {
 public:
  // Loads and checks the model (ModelError) and maps its classes to levels (ConfigError, see
  // DynamicClassTable::fromConfig). Sets OpenCV's thread count to config.threads.
  Detector(const DetectorConfig& config, const Config& dynamic_classes);

  // Letterbox, inference, decode, per-class NMS, back to image pixels. bgr: CV_8UC3, any size.
  std::vector<Detection> detect(const cv::Mat& bgr, StageTimes* times = nullptr);

  std::string modelName() const { return model_.name(); }
  const std::vector<std::string>& classNames() const { return model_.classNames(); }
  const DetectorConfig& config() const { return config_; }

 private:
  DetectorConfig config_;
  YoloModel model_;
  DynamicClassTable levels_;
  cv::Mat square_;  // reused letterbox buffer
};

}  // namespace bmp::detector

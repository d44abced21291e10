#include "detector/lcm/detections_message.hpp"

#include <cmath>

namespace bmp::detector {

static_assert(static_cast<int>(DynamicLevel::kHigh) == detection_t::LEVEL_HIGH &&
              static_cast<int>(DynamicLevel::kMedium) == detection_t::LEVEL_MEDIUM &&
              static_cast<int>(DynamicLevel::kLow) == detection_t::LEVEL_LOW);
static_assert(kMaxDetectionsPerFrame == detections_t::MAX_DETECTIONS);

detections_t toDetectionsMessage(const FrameResult& result, const std::string& model) {
  detections_t msg;
  msg.utime = result.utime;
  msg.seq = result.seq;
  msg.model = model;
  msg.inference_ms = static_cast<float>(result.total_ms);
  msg.image_width = result.width;
  msg.image_height = result.height;
  msg.skipped = result.ok ? "" : (result.error.empty() ? "not processed" : result.error);
  if (!result.ok) {
    msg.num_detections = 0;
    return msg;
  }
  for (const auto& d : result.detections) {
    detection_t box;
    box.x = d.box.x;
    box.y = d.box.y;
    box.width = d.box.width;
    box.height = d.box.height;
    box.class_id = static_cast<int16_t>(d.class_id);
    box.label = d.label;
    box.score = d.score;
    box.dynamic_level = static_cast<int8_t>(d.level);
    msg.detections.push_back(std::move(box));
  }
  msg.num_detections = static_cast<int32_t>(msg.detections.size());
  return msg;
}

namespace {

const int kCocoClasses = 80;  // detection_t.class_id is a COCO index

void check(bool ok, const detections_t& msg, const std::string& what) {
  if (!ok) throw DetectionsMessageError("detections for frame seq " + std::to_string(msg.seq) + ": " + what);
}

}  // namespace

FrameDetections fromDetectionsMessage(const detections_t& msg) {
  FrameDetections out;
  out.seq = msg.seq;
  out.utime = msg.utime;
  out.model = msg.model;
  out.width = msg.image_width;
  out.height = msg.image_height;
  out.inference_ms = msg.inference_ms;
  out.skipped = msg.skipped;
  if (!out.skipped.empty()) {
    check(msg.detections.empty(), msg, "skipped (" + msg.skipped + ") yet carries boxes");
    return out;
  }
  check(msg.image_width > 0 && msg.image_height > 0, msg,
        "image size " + std::to_string(msg.image_width) + "x" + std::to_string(msg.image_height));
  check(msg.num_detections <= detections_t::MAX_DETECTIONS, msg,
        std::to_string(msg.num_detections) + " boxes, over the " +
            std::to_string(detections_t::MAX_DETECTIONS) + " a detector may send");
  // Boxes are clipped to the image by the detector; a pixel of slack allows for float rounding.
  const float slack = 1.0f;
  for (std::size_t i = 0; i < msg.detections.size(); ++i) {
    const detection_t& b = msg.detections[i];
    const std::string which = "box " + std::to_string(i) + " (" + b.label + ")";
    check(b.dynamic_level >= detection_t::LEVEL_LOW && b.dynamic_level <= detection_t::LEVEL_HIGH, msg,
          which + ": unknown dynamic level " + std::to_string(b.dynamic_level));
    check(std::isfinite(b.x) && std::isfinite(b.y) && std::isfinite(b.width) && std::isfinite(b.height) &&
              b.width > 0.0f && b.height > 0.0f,
          msg, which + ": not a box");
    check(b.x >= -slack && b.y >= -slack && b.x + b.width <= static_cast<float>(msg.image_width) + slack &&
              b.y + b.height <= static_cast<float>(msg.image_height) + slack,
          msg,
          which + ": outside the " + std::to_string(msg.image_width) + "x" +
              std::to_string(msg.image_height) + " image");
    check(b.class_id >= 0 && b.class_id < kCocoClasses, msg,
          which + ": class " + std::to_string(b.class_id) + " is not a COCO index (0..79)");
    check(std::isfinite(b.score) && b.score >= 0.0f && b.score <= 1.0f, msg,
          which + ": score " + std::to_string(b.score) + " outside [0, 1]");
    Detection d;
    d.box = cv::Rect2f(b.x, b.y, b.width, b.height);
    d.class_id = b.class_id;
    d.label = b.label;
    d.score = b.score;
    d.level = static_cast<DynamicLevel>(b.dynamic_level);
    out.detections.push_back(std::move(d));
  }
  return out;
}

}  // namespace bmp::detector

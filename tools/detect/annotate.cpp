#include "annotate.hpp"

#include <cstdio>
#include <sstream>

#include <opencv2/imgproc.hpp>

#include "bmp/common/json_text.hpp"

namespace bmp::detect_tools {

using detector::DynamicLevel;

cv::Scalar levelColour(DynamicLevel level) {
  switch (level) {
    case DynamicLevel::kHigh:
      return {0, 0, 255};
    case DynamicLevel::kMedium:
      return {0, 165, 255};
    case DynamicLevel::kLow:
      break;
  }
  return {0, 200, 0};
}

void drawDetections(cv::Mat& bgr, const std::vector<detector::Detection>& detections) {
  const int thickness = std::max(1, std::min(bgr.cols, bgr.rows) / 240);
  const double font_scale = std::max(0.4, std::min(bgr.cols, bgr.rows) / 900.0);
  // Lowest score first, so the most confident labels end up on top.
  for (auto it = detections.rbegin(); it != detections.rend(); ++it) {
    const cv::Scalar colour = levelColour(it->level);
    const cv::Rect box(it->box);
    cv::rectangle(bgr, box, colour, thickness);
    char text[96];
    std::snprintf(text, sizeof(text), "%s %.2f", it->label.c_str(), it->score);
    int baseline = 0;
    const cv::Size size = cv::getTextSize(text, cv::FONT_HERSHEY_SIMPLEX, font_scale, 1, &baseline);
    const int top = box.y - size.height - baseline >= 0 ? box.y - size.height - baseline : box.y;
    // A box at the right edge keeps its whole label: the label moves left into the image.
    const int left = std::max(0, std::min(box.x, bgr.cols - size.width - 2));
    cv::rectangle(bgr, cv::Rect(left, top, size.width + 2, size.height + baseline), colour, cv::FILLED);
    cv::putText(bgr, text, {left + 1, top + size.height}, cv::FONT_HERSHEY_SIMPLEX, font_scale,
                cv::Scalar::all(255), 1, cv::LINE_AA);
  }
}

std::string detectionsJson(const std::string& image, double stamp, const std::string& model, int width,
                           int height, double total_ms, const std::vector<detector::Detection>& detections) {
  std::ostringstream out;
  out.precision(6);
  out << "{\"image\": " << jsonString(image) << ", \"stamp\": " << std::fixed << stamp << std::defaultfloat
      << ", \"model\": " << jsonString(model) << ", \"width\": " << width << ", \"height\": " << height
      << ", \"total_ms\": " << total_ms << ", \"detections\": [";
  for (std::size_t i = 0; i < detections.size(); ++i) {
    const auto& d = detections[i];
    out << (i ? ", " : "") << "{\"label\": " << jsonString(d.label) << ", \"class_id\": " << d.class_id
        << ", \"score\": " << d.score << ", \"level\": " << jsonString(detector::toString(d.level))
        << ", \"box\": [" << d.box.x << ", " << d.box.y << ", " << d.box.width << ", " << d.box.height
        << "]}";
  }
  out << "]}";
  return out.str();
}

}  // namespace bmp::detect_tools

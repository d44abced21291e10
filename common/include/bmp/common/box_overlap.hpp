#pragma once
// Overlap of two image boxes, shared by the detector's NMS and the tracker's stand-in boxes.
#include <opencv2/core.hpp>

namespace bmp {

// Intersection over union; 0 when both boxes are empty.
inline float iou(const cv::Rect2f& a, const cv::Rect2f& b) {
  const float overlap = (a & b).area();
  const float sum = a.area() + b.area() - overlap;
  return sum > 0.0f ? overlap / sum : 0.0f;
}

}  // namespace bmp

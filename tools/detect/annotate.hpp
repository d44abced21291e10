#pragma once
// Showing what the detector saw: boxes coloured by dynamic level (high red, medium orange, low green) with
// label and score, and the same as JSON.
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "detector/detector.hpp"

namespace bmp::detect_tools {

cv::Scalar levelColour(detector::DynamicLevel level);  // BGR
void drawDetections(cv::Mat& bgr, const std::vector<detector::Detection>& detections);

// One JSON object on one line: {"image": ..., "stamp": ..., "model": ..., "width": ..., "height": ...,
// "total_ms": ..., "detections": [{"label", "class_id", "score", "level", "box": [x, y, w, h]}, ...]}
std::string detectionsJson(const std::string& image, double stamp, const std::string& model, int width,
                           int height, double total_ms, const std::vector<detector::Detection>& detections);

}  // namespace bmp::detect_tools

#include "detector/yolo_decode.hpp"

#include <algorithm>
#include <stdexcept>

namespace bmp::detector {

std::vector<Candidate> decodeRows(const cv::Mat& rows, ScoreLayout layout, float coord_scale,
                                  float conf_threshold) {
  if (rows.type() != CV_32F || rows.dims != 2 || rows.cols < 6)
    throw std::invalid_argument("decodeRows needs N x (5 + classes) CV_32F rows");
  const int num_classes = rows.cols - 5;
  std::vector<Candidate> out;
  for (int r = 0; r < rows.rows; ++r) {
    const float* row = rows.ptr<float>(r);
    const float objectness = row[4];
    // Confidence never exceeds objectness, so most rows are rejected before the class scan.
    if (objectness < conf_threshold) continue;
    const float* scores = row + 5;
    const int best = static_cast<int>(std::max_element(scores, scores + num_classes) - scores);
    const float score =
        layout == ScoreLayout::kObjectnessTimesClass ? objectness * scores[best] : scores[best];
    if (score < conf_threshold) continue;
    const float cx = row[0] * coord_scale, cy = row[1] * coord_scale;
    const float w = row[2] * coord_scale, h = row[3] * coord_scale;
    out.push_back({cv::Rect2f(cx - w / 2, cy - h / 2, w, h), best, score});
  }
  return out;
}

std::vector<Candidate> nmsPerClass(std::vector<Candidate> candidates, float iou_threshold,
                                   int max_detections) {
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const Candidate& a, const Candidate& b) { return a.score > b.score; });
  std::vector<Candidate> kept;
  for (const auto& c : candidates) {
    if (static_cast<int>(kept.size()) >= max_detections) break;
    const bool suppressed = std::any_of(kept.begin(), kept.end(), [&](const Candidate& k) {
      return k.class_id == c.class_id && iou(k.box, c.box) > iou_threshold;
    });
    if (!suppressed) kept.push_back(c);
  }
  return kept;
}

}  // namespace bmp::detector

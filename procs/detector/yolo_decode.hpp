#pragma once
// From raw YOLO output rows to boxes: confidence threshold, then non-maximum suppression per class.
#include <vector>

#include <opencv2/core.hpp>

#include "bmp/common/box_overlap.hpp"  // iou, for NMS

namespace bmp::detector {

struct Candidate {
  cv::Rect2f box;  // top-left, size; network-input pixels until mapped back
  int class_id = 0;
  float score = 0.0f;
};

enum class ScoreLayout {
  kObjectnessTimesClass,     // YOLOv5 ONNX: column 4 objectness, 5.. class probabilities
  kClassIncludesObjectness,  // OpenCV's darknet region layer: 5.. already multiplied by objectness
};

// rows: N x (5 + classes) CV_32F, each cx, cy, w, h, objectness, class scores. coord_scale multiplies the
// box columns (1 for YOLOv5, which gives input pixels; the input size for darknet, which gives 0..1).
// Keeps, per row, the best class when its confidence reaches conf_threshold.
std::vector<Candidate> decodeRows(const cv::Mat& rows, ScoreLayout layout, float coord_scale,
                                  float conf_threshold);

// Greedy NMS within each class: highest score first, drops boxes overlapping a kept one of the same
// class by more than iou_threshold. Returns at most max_detections, best first.
std::vector<Candidate> nmsPerClass(std::vector<Candidate> candidates, float iou_threshold,
                                   int max_detections);

}  // namespace bmp::detector

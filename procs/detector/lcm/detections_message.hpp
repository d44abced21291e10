#pragma once
// The DETECTIONS contract (lcmtypes/detections_t.lcm) both ways: bmp-detector writes it, and a subscriber
// (the tracker's dynamic stage, tests) reads it back, checked, as the library's types.
#include <stdexcept>
#include <string>
#include <vector>

#include <bmp/detections_t.hpp>

#include "detector/detection_worker.hpp"
#include "detector/detector.hpp"

namespace bmp::detector {

// A DETECTIONS message that does not describe boxes in an image: names the frame and what is wrong.
class DetectionsMessageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct FrameDetections {
  int64_t seq = 0;
  int64_t utime = 0;
  std::string model;
  int width = 0;  // the colour image the boxes refer to
  int height = 0;
  double inference_ms = 0.0;
  std::string skipped;  // why the detector could not process the frame ("" when it did; no boxes then)
  std::vector<Detection> detections;
};

// A result that is not ok becomes the answer for a skipped frame: its error as the reason, no boxes.
detections_t toDetectionsMessage(const FrameResult& result, const std::string& model);

// Throws DetectionsMessageError for an unknown level, a class outside COCO's 0..79, a non-finite or empty
// box, a box outside the image, a score outside [0, 1], an image without size, more boxes than
// detections_t::MAX_DETECTIONS, or a skipped frame that carries boxes: another publisher's message is not
// trusted blindly.
FrameDetections fromDetectionsMessage(const detections_t& msg);

}  // namespace bmp::detector

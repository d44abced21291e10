#pragma once
// The paper's dynamic-region test (An et al. 2025, section 3.2), per keypoint: the observation z = d when
// the keypoint lies inside a high-dynamic box and outside every low-dynamic box, else z = s. A low-dynamic
// object inside a person's box (a monitor behind someone) keeps its keypoints static. Medium-dynamic
// objects (chairs, cups) count as dynamic only with evidence that they move: our rule, since the paper
// leaves it open (see movingMediumBoxes).
#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

#include "bmp/common/dynamic_level.hpp"

namespace bmp::tracker {

struct ObjectBox {
  cv::Rect2f box;  // distorted image pixels, as the detector saw the colour image
  DynamicLevel level = DynamicLevel::kLow;
  int class_id = -1;
  float score = 0.0f;
};

// The detector's detections as the dynamic stage's boxes. A template over the detection type
// (detector::Detection: box, level, class_id, score), so this library does not depend on the detector's.
template <typename Detections>
std::vector<ObjectBox> toObjectBoxes(const Detections& detections) {
  std::vector<ObjectBox> boxes;
  boxes.reserve(detections.size());
  for (const auto& d : detections) boxes.push_back({d.box, d.level, d.class_id, d.score});
  return boxes;
}

struct RegionOptions {
  // A medium-dynamic box counts as moving when at least this share of its area lies inside one
  // high-dynamic box: an object in a person's hands moves with the person.
  float medium_held_overlap = 0.5f;
  // ... or when at least this share of its keypoints judged by the geometric observation in the last frame
  // moved against the camera motion: a chair that is being pushed (Frame::moved; kGeometric only).
  float medium_moving_keypoints = 0.5f;
};

// Which boxes count as dynamic (z = d) regions: every high box, and each medium box with evidence it
// moves. moving_share[i] is the share of box i's keypoints seen moving (movedShareInBoxes; empty: none
// known).
std::vector<uint8_t> movingBoxes(const std::vector<ObjectBox>& boxes, const RegionOptions& options,
                                 const std::vector<float>& moving_share = {});

// Per keypoint: 1 (z = d) when it lies inside a moving box and inside no low-dynamic box, else 0 (z = s).
std::vector<uint8_t> observeRegions(const std::vector<cv::KeyPoint>& keys,
                                    const std::vector<ObjectBox>& boxes, const std::vector<uint8_t>& moving);

// Per box, the share of the keypoints inside it with a verdict (>= 0) whose verdict is 1 (moved); 0 when
// fewer than min_moved moved (for movingBoxes' moving_share: a lone moved keypoint may be a mismatch).
std::vector<float> movedShareInBoxes(const std::vector<cv::KeyPoint>& keys,
                                     const std::vector<ObjectBox>& boxes, const std::vector<int8_t>& verdict,
                                     int min_moved);

// Boxes seen age_s before the frame they stand in for (real time: the frame's own answer has not come):
// each high or medium box grown by growth_px_per_s * age_s on every side, as far as a mover may have gone
// meanwhile. Low-dynamic boxes stay as they were: they do not move, and a grown one would hide a person.
std::vector<ObjectBox> grownForAge(std::vector<ObjectBox> boxes, double age_s, double growth_px_per_s);

// The newest answer's boxes (of every level) moved on by age_s at the image speed each showed since the
// answer before it (dt_s earlier): each box takes the shift of the earlier box of its class that overlaps
// it most (intersection over union at least min_iou); a box with no such partner stays where it was.
// A person crossing the view is where the box says, not only somewhere in a box grown to every side.
std::vector<ObjectBox> movedForAge(std::vector<ObjectBox> newest, const std::vector<ObjectBox>& before,
                                   double dt_s, double age_s, double min_iou);

}  // namespace bmp::tracker

#pragma once
// A person the detector found in two answers in a row and then misses is held: the frame's boxes get that
// person's box, moved on at the speed its last two answers showed, until the detector finds them again or
// held_box_s has passed. YOLO misses a person now and then and finds them a frame or two later (a score
// just under the threshold, a turn, an arm across the body). Without the box, each such frame is a static
// observation for the person's keypoints: their moving probability falls within 2-3 frames, and keypoints
// first seen then start at 0.5 and fall below the threshold, so they enter the pose and the map.
#include <optional>
#include <vector>

#include <opencv2/core/types.hpp>

#include "tracker/dynamic_regions.hpp"

namespace bmp::tracker {

class HeldBoxes {
 public:
  // hold_s: how long a missed box is held (0: never). partner_iou: a box in the next answer is the same
  // object when it has the same class and overlaps the held box, moved on to the answer's time, by at least
  // this (intersection over union).
  HeldBoxes(double hold_s, double partner_iou);

  // The frame's boxes with the held ones added (high-dynamic classes only: persons and animals). No answer
  // (nullopt) stays no answer and changes nothing: the moving probabilities carry on from the matches.
  // Frames come in time order; a stamp that goes back forgets every held box.
  std::optional<std::vector<ObjectBox>> complete(const std::optional<std::vector<ObjectBox>>& boxes,
                                                 double stamp_s);

 private:
  struct Held {
    ObjectBox box;         // as last found
    double found_s = 0.0;  // when
    cv::Point2f velocity;  // image pixels per second, from the two answers before
    bool moving = false;   // found in two answers in a row: its speed is known and it may be held
    cv::Rect2f at(double stamp_s) const;
  };

  double hold_s_;
  double partner_iou_;
  double last_s_ = 0.0;
  std::vector<Held> held_;
};

}  // namespace bmp::tracker

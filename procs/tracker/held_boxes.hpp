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
  // A late answer (real time: it came after its frame was tracked). Not older than the answers before it,
  // it is complete()'s next answer, held boxes learn from it too. Older (a later frame's answer came
  // first), it is completed with each held box as it stands moved back to stamp_s, while that lies within
  // hold_s of when it was last found, and changes nothing held.
  std::vector<ObjectBox> completeLate(const std::vector<ObjectBox>& boxes, double stamp_s);

 private:
  struct Held {
    ObjectBox box;         // as last found
    double found_s = 0.0;  // when
    cv::Point2f velocity;  // image pixels per second, from the two answers before
    bool moving = false;   // found in two answers in a row: its speed is known and it may be held
    cv::Rect2f at(double stamp_s) const;
    ObjectBox boxAt(double stamp_s) const;  // the box, moved to stamp_s
  };

  // The held box (not yet taken) that b is: same class, overlapping where that one would be at stamp_s by
  // at least partner_iou (the most); -1 for none.
  int partnerOf(const ObjectBox& b, double stamp_s, const std::vector<bool>& taken) const;

  // The held boxes not taken that may stand in at stamp_s: moving, and found within hold_s of it.
  std::vector<std::size_t> missedAt(double stamp_s, const std::vector<bool>& taken) const;

  double hold_s_;
  double partner_iou_;
  double last_s_ = 0.0;
  std::vector<Held> held_;
};

}  // namespace bmp::tracker

#pragma once
// Keypoint-to-keypoint tracks between consecutive frames, for keypoints that matched no map point. A mover
// the detector does not know is rarely matched to the map: its points move further each frame than the
// motion model's window. Matched to the last frame's keypoints over a wide window around where each would
// be if it were static, its keypoints give the geometric observation something to judge, and each takes
// its prior from the last frame's keypoint (the paper's second source of priors).
#include <vector>

#include "tracker/frame.hpp"

namespace bmp::tracker {

struct KeypointTrackOptions {
  double radius_px = 40.0;  // search window around the static prediction, level-0 pixels
  int max_distance = 50;    // Hamming distance
  double ratio = 0.8;       // best over second best within the window
};

// Per keypoint of `frame`: the index of its last-frame keypoint, or -1. Only keypoints with `open[i]`
// set get one; each last-frame keypoint with depth is projected into `frame` with both poses, and its
// best descriptor match in the window (any level within one of its own) must pass the ratio test, be
// open, and not be taken by a closer match.
std::vector<int> trackFromLastFrame(const Frame& frame, const Frame& last, const FrameGeometry& g,
                                    const std::vector<uint8_t>& open, const KeypointTrackOptions& options);

}  // namespace bmp::tracker

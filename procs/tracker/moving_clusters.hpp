#pragma once
// Movers found by geometry alone: keypoints whose residual says they moved, linked when close in the
// image and in depth, make clusters; a cluster of enough of them is taken for one body, and its bounding
// box and depth range cover that body's other keypoints (most of a mover's keypoints are new in each
// frame, so few have a residual of their own).
#include <cstdint>
#include <vector>

#include "tracker/frame.hpp"

namespace bmp::tracker {

struct MovingCluster {
  int size = 0;                           // keypoints that moved
  double u0 = 0, v0 = 0, u1 = 0, v1 = 0;  // bounding box, undistorted pixels
  double near_m = 0, far_m = 0;           // depth range of its keypoints
  bool covers(double u, double v, double depth, double margin_m) const {
    return u >= u0 && u <= u1 && v >= v0 && v <= v1 && depth >= near_m - margin_m &&
           depth <= far_m + margin_m;
  }
};

// verdict: per keypoint, what its residual said: 1 moved, 0 stayed, -1 nothing. Keypoints with depth that
// moved are linked within link_px in the image and link_depth_m in depth. Returned: the clusters of at
// least min_size whose box and depth range hold no more keypoints that stayed than moved (a mover's region
// is mostly mover; a few mismatches strung across a static wall are not, and must not take it out of the
// pose).
std::vector<MovingCluster> movingClusters(const Features& f, const FrameGeometry& g,
                                          const std::vector<int8_t>& verdict, double link_px,
                                          double link_depth_m, int min_size);

}  // namespace bmp::tracker

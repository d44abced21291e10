#pragma once
// Temporary points (tracking.temporal_points, off by default): the last frame's nearest keypoints with
// depth and no map point get a point of their own for the motion model to match, where the map is thin.
// They never enter the map.
#include "tracker/frame.hpp"

namespace bmp::tracker {

// Up to max_points of last's nearest keypoints with depth, skipping those the dynamic stage saw as dynamic
// (a person's keypoint would carry the person's motion into the pose). Returns how many were made.
int addTemporaryPoints(Frame& last, const FrameGeometry& g, int max_points);

}  // namespace bmp::tracker

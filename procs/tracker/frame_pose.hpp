#pragma once
// Pose-only optimisation of a frame against its matched map points: the glue between Frame and
// optimizePose. Excluded keypoints are left out; keypoint weights scale their cost.
#include "tracker/frame.hpp"
#include "tracker/pose_optimizer.hpp"
#include "tracker/tracker_options.hpp"

namespace bmp::tracker {

class MapPoint;

// Whether a map point counts fully in the pose: seen by enough keyframes, over a long enough time.
bool isMature(const MapPoint& mp, const PoseOptimizerOptions& options);

// Sets the frame's pose and outlier flags; returns the number of inliers.
// prior: where the frame should be (MotionPrior), or null.
// position_std_m: if given, set to how well the inliers pin the position (positionStd; infinity with fewer
// than 3 observations). Only the frame's last solve needs it, so the others skip the work.
int optimizeFramePose(Frame& frame, const FrameGeometry& g, const PoseOptimizerOptions& options,
                      const PositionPrior* prior = nullptr, double* position_std_m = nullptr);
// Unmatches the outliers; returns the matches left that are map points (not temporary ones).
int dropOutliers(Frame& frame);

}  // namespace bmp::tracker

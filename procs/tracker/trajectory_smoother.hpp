#pragma once
// The written trajectory's positions, smoothed. Each tracked frame's position is a measurement whose
// standard deviation is the frame's position_std_m (how well its inliers pin it); the camera's acceleration
// between frames is a zero-mean error of accel_sigma. The positions that best fit both (least squares, one
// banded system per stretch of frames) keep a well-pinned frame where it is and pull a weakly pinned one,
// as in a crowd that leaves only a far band of the room in view, towards the path its neighbours show.
// accel_sigma is a floor: a camera that moves harder than it (a shaken hand-held one) has its own
// acceleration measured from the stretch's positions over accel_lag_s, where the frames' noise is small
// beside it, and that is used instead, so a fast camera's real motion is not smoothed away. Orientation is
// not changed. A stretch ends where tracking was lost (the next frame relocalised), where the stamps go back
// or jump more than max_gap_s: no motion links the frames across such a break.
#include <optional>
#include <vector>

#include <Eigen/Core>

namespace bmp::tracker {

struct SmootherSample {
  double stamp = 0.0;  // seconds
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  double std_m = 0.0;           // the position's standard deviation; not finite or <= 0: unknown
  bool starts_stretch = false;  // tracking began again here (relocalised): no link to the frame before
};

struct SmootherOptions {
  double accel_sigma = 1.0;  // m/s^2, per axis; 0: off (positions returned as they are)
  double accel_lag_s = 0.2;  // the camera's own acceleration measured over this (0: accel_sigma always)
  double max_gap_s = 0.5;    // frames further apart than this are not linked
};

// The camera's acceleration per axis (RMS, m/s^2) in samples [begin, end), measured by second differences
// over lag_s with the frames' own noise taken out; none when the stretch is too short to tell.
std::optional<double> measuredAccelSigma(const std::vector<SmootherSample>& samples, std::size_t begin,
                                         std::size_t end, double lag_s);

// The smoothed positions, one per sample, in order. A frame whose std is unknown is weighed as its
// stretch's median; a stretch of fewer than 3 frames, or without any known std, is left as it is.
std::vector<Eigen::Vector3d> smoothPositions(const std::vector<SmootherSample>& samples,
                                             const SmootherOptions& options);

}  // namespace bmp::tracker

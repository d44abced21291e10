#pragma once
// Absolute trajectory error as the TUM benchmark computes it: associate stamps, align with a rigid
// transform (Horn/Umeyama, no scale), RMSE of the translation differences.
#include "bmp/common/se3.hpp"
#include "bmp/common/tum_trajectory.hpp"

namespace bmp::tracker {

struct AteResult {
  int matched = 0;
  double rmse = 0.0, mean = 0.0, median = 0.0, max = 0.0;  // metres
  SE3 T_gt_est = SE3::Identity();                          // the alignment
};

// Each estimate stamp takes the nearest ground-truth stamp within max_dt. Throws std::runtime_error when
// fewer than 3 pairs associate.
AteResult computeAte(const Trajectory& estimate, const Trajectory& groundtruth, double max_dt = 0.02);

}  // namespace bmp::tracker

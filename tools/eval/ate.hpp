#pragma once
// Absolute trajectory error as evaluate_ate.py computes it: associate stamps, align the estimated
// positions (times scale) to the ground truth with Horn's method, report the position errors.
#include <vector>

#include "bmp/common/tum_trajectory.hpp"
#include "eval/alignment.hpp"
#include "eval/association.hpp"
#include "eval/error_stats.hpp"

namespace bmp::eval {

struct AteOptions {
  double max_difference = 0.02;  // seconds
  double offset = 0.0;           // added to estimated stamps
  double scale = 1.0;            // applied to estimated positions
};

struct AtePair {
  double gt_stamp = 0.0;
  double est_stamp = 0.0;
  Eigen::Vector3d gt_position = Eigen::Vector3d::Zero();
  Eigen::Vector3d aligned_position = Eigen::Vector3d::Zero();  // estimate after scale and alignment
  double error = 0.0;                                          // metres
};

struct AteResult {
  std::vector<AtePair> pairs;  // ordered by ground-truth stamp
  RigidAlignment alignment;    // maps scaled estimated positions into the ground-truth frame
  ErrorStats stats;            // metres
};

// gt and est sorted with unique stamps (see loadTrajectory). Throws EvalError when fewer than two stamps
// associate.
AteResult computeAte(const Trajectory& gt, const Trajectory& est, const AteOptions& options = {});

// The whole estimate moved into the ground-truth frame: positions scaled, then aligned; orientations
// rotated by the same alignment.
Trajectory alignedTrajectory(const Trajectory& est, const RigidAlignment& alignment, double scale);

}  // namespace bmp::eval

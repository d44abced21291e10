#pragma once
// Relative pose error as evaluate_rpe.py --fixed_delta computes it. Two deliberate differences: all pairs
// are kept (the script samples 10000 at random when there are more), and too few pairs give an empty
// result instead of an exception.
//
// The error of a pair (i, j) is the script's ominus(scale(ominus(E_j, E_i)), ominus(G_j, G_i)) with
// ominus(a, b) = inv(a) * b, i.e. inv(scale(inv(E_j) * E_i)) * inv(G_j) * G_i.
#include <cstddef>
#include <string>
#include <vector>

#include "bmp/common/tum_trajectory.hpp"
#include "eval/error_stats.hpp"

namespace bmp::eval {

enum class DeltaUnit { kSeconds, kFrames };

struct RpeOptions {
  double delta = 1.0;
  DeltaUnit unit = DeltaUnit::kSeconds;
  double offset = 0.0;  // added to estimated stamps
  double scale = 1.0;   // applied to estimated relative translations
};

struct RpePair {
  std::size_t i = 0, j = 0;  // estimate indices
  double est_stamp_0 = 0.0, est_stamp_1 = 0.0;
  double gt_stamp_0 = 0.0, gt_stamp_1 = 0.0;
  double trans_error = 0.0;  // metres
  double rot_error = 0.0;    // radians
};

struct RpeResult {
  std::vector<RpePair> pairs;
  double gt_interval = 0.0;  // median ground-truth stamp spacing; pairs further than 2x from gt are skipped
  ErrorStats trans;          // metres
  ErrorStats rot_deg;        // degrees
};

// The script's binary search: not always the closest element of an unsorted list, but exactly the
// element the script picks. L must be non-empty.
std::size_t findClosestIndex(const std::vector<double>& L, double t);

// gt and est sorted with unique stamps.
RpeResult computeRpe(const Trajectory& gt, const Trajectory& est, const RpeOptions& options = {});

// "s" or "f"; throws EvalError otherwise.
DeltaUnit parseDeltaUnit(const std::string& text);
const char* deltaUnitName(DeltaUnit unit);

}  // namespace bmp::eval

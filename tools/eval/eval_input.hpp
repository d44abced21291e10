#pragma once
// Loading trajectories for evaluation. The TUM scripts key poses by stamp in a dict, so a repeated stamp
// keeps the pose of its last line; we do the same.
#include <string>

#include "bmp/common/tum_trajectory.hpp"

namespace bmp::eval {

// Sorted by stamp, stamps unique. Throws EvalError naming the file (and line, for a malformed line), or
// when the file holds no pose at all.
Trajectory loadTrajectory(const std::string& path);
// Removes repeated stamps from a sorted trajectory, keeping the last pose given for each stamp.
Trajectory uniqueStamps(const Trajectory& sorted);

}  // namespace bmp::eval

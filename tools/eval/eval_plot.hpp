#pragma once
// PNG plots of an evaluation, drawn with OpenCV.
#include <string>

#include "bmp/common/tum_trajectory.hpp"
#include "eval/ate.hpp"
#include "eval/rpe.hpp"

namespace bmp::eval {

// Top view (x-y plane of the ground-truth frame, equal axis scale): ground truth, aligned estimate and thin
// links between associated pairs. Throws EvalError when the file cannot be written.
void plotTrajectoryTopView(const std::string& path, const Trajectory& gt, const Trajectory& aligned_est,
                           const AteResult& ate, const std::string& title);

// Two panels over time since the first ground-truth stamp: ATE per associated pair and RPE translational
// error per pose pair (at the pair's first stamp).
void plotErrorsOverTime(const std::string& path, const AteResult& ate, const RpeResult& rpe, double t0,
                        const std::string& rpe_caption, const std::string& title);

}  // namespace bmp::eval

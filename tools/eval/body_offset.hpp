#pragma once
// Whether the ground truth's orientations are camera orientations. A motion-capture ground truth often gives
// the pose of a marker body fixed to the camera (Bonn RGB-D Dynamic: about 176 degrees off): positions, and
// so the ATE, are fine, but the RPE then compares motions expressed in different frames. This measures the
// rotation between the estimate's frame and the ground truth's, pose by pose, after the ATE alignment.
#include <cstddef>

#include "bmp/common/tum_trajectory.hpp"
#include "eval/ate.hpp"

namespace bmp::eval {

struct BodyOffset {
  std::size_t pairs = 0;
  double angle_deg = 0.0;   // the mean rotation from the estimate's camera frame to the ground truth's body
  double spread_deg = 0.0;  // median angle between each pair's rotation and the mean
  // A large, steady offset: the ground truth's orientations are not camera orientations.
  bool constant() const;
};

// est_offset: the seconds added to estimated stamps for the association (AteOptions::offset).
BodyOffset measureBodyOffset(const Trajectory& gt, const Trajectory& est, const AteResult& ate,
                             double est_offset);

}  // namespace bmp::eval

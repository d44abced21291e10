#pragma once
// Where the camera should be, by a constant-velocity model with a smoothed velocity: a prior on the frame's
// position for the pose optimiser. Keypoints leave one motion barely seen when the scene's depths are alike
// (a far wall, a desk at one distance): a sideways shift with a turn that keeps the scene in place. Without
// a prior the frame positions jitter along it, by several centimetres on Bonn `crowd` at 5.4-5.7 s.
#include <optional>

#include <Eigen/Core>

#include "tracker/pose_optimizer.hpp"
#include "tracker/tracker_options.hpp"

namespace bmp::tracker {

class MotionPrior {
 public:
  explicit MotionPrior(const PoseOptimizerOptions& options) : options_(options) {}

  // A tracked frame dt after the last: its velocity is blended into the smoothed one.
  void observe(const Eigen::Vector3d& last_center, const Eigen::Vector3d& center, double dt);
  // The velocity is not known any more (lost, relocalised, input went back in time).
  void reset() { velocity_.reset(); }
  // The prior for a frame dt after the last tracked one at last_center; none before a velocity is known,
  // or when the prior is off.
  std::optional<PositionPrior> predict(const Eigen::Vector3d& last_center, double dt) const;

 private:
  PoseOptimizerOptions options_;
  std::optional<Eigen::Vector3d> velocity_;  // m/s, world frame
};

}  // namespace bmp::tracker

#pragma once
// Where the camera should be, by a constant-velocity model with a smoothed velocity: a prior on the frame's
// position for the pose optimiser. Keypoints leave one motion barely seen when the scene's depths are alike
// (a far wall, a desk at one distance): a sideways shift with a turn that keeps the scene in place. Without
// a prior the frame positions jitter along it, by several centimetres on Bonn `crowd` at 5.4-5.7 s.
// The prior's spread is that of an acceleration of motion_prior_accel at least. A camera that moves harder
// (a shaken hand-held one) has its acceleration measured from the frames tracked over the last
// motion_prior_accel_window_s, and the spread widened to what the prediction then misses by. Until that
// window has frames enough (after the start, or a loss), the camera's motion is not known, and the spread
// stands for motion_prior_accel_unmeasured (twice the floor). The first frames decide: held to the floor
// until measured, shaken_camera seeds 1-2 in real time (mapping in its thread) were pulled off their path
// for good in 8 of 11 runs (10-46 cm ATE), at 1.5 x the floor in 6 of 10, at 2 x in none of 10 (3.3-5 mm);
// shaken from rest (camera_ramp_s: 1), seed 2 in 4 of 4 (3 cm or more) against none at 2 x. No prior at all
// until measured costs the crowd scenes more (seed 3: 7.1 -> 13 mm) than 2 x does.
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "tracker/pose_optimizer.hpp"
#include "tracker/tracker_options.hpp"
#include "tracker/trajectory_smoother.hpp"

namespace bmp::tracker {

class MotionPrior {
 public:
  explicit MotionPrior(const PoseOptimizerOptions& options) : options_(options) {}

  // A tracked frame dt after the last (at last_center): its velocity is blended into the smoothed one, and
  // its position (with its position_std_m) joins the ones the acceleration is measured from.
  void observe(const Eigen::Vector3d& last_center, double dt, const SmootherSample& frame);
  // The velocity is not known any more (lost, relocalised, input went back in time).
  void reset();
  // The prior for a frame dt after the last tracked one at last_center; none before a velocity is known,
  // or when the prior is off.
  std::optional<PositionPrior> predict(const Eigen::Vector3d& last_center, double dt) const;
  // The acceleration the spread stands for (m/s^2): the floor, or more for a camera measured to move harder.
  double accel() const;

 private:
  PoseOptimizerOptions options_;
  std::optional<Eigen::Vector3d> velocity_;  // m/s, world frame
  std::vector<SmootherSample> recent_;       // the frames tracked over the last motion_prior_accel_window_s
  std::optional<double> measured_accel_;     // m/s^2 per axis (RMS) over recent_; none: too few to tell
};

}  // namespace bmp::tracker

#include "tracker/motion_prior.hpp"

namespace bmp::tracker {

void MotionPrior::observe(const Eigen::Vector3d& last_center, const Eigen::Vector3d& center, double dt) {
  if (dt <= 0.0) return;
  const Eigen::Vector3d v = (center - last_center) / dt;
  const double gain = options_.motion_prior_velocity_gain;
  velocity_ = velocity_ ? Eigen::Vector3d((1.0 - gain) * *velocity_ + gain * v) : v;
}

std::optional<PositionPrior> MotionPrior::predict(const Eigen::Vector3d& last_center, double dt) const {
  if (!velocity_ || options_.motion_prior_accel <= 0.0 || dt <= 0.0) return std::nullopt;
  // An unknown acceleration a moves the camera by a dt^2 / 2 from the constant-velocity path.
  return PositionPrior{last_center + *velocity_ * dt, 0.5 * options_.motion_prior_accel * dt * dt};
}

}  // namespace bmp::tracker

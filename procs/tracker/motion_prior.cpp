#include "tracker/motion_prior.hpp"

#include <algorithm>

namespace bmp::tracker {

void MotionPrior::observe(const Eigen::Vector3d& last_center, double dt, const SmootherSample& frame) {
  if (dt <= 0.0) return;
  const Eigen::Vector3d v = (frame.position - last_center) / dt;
  const double gain = options_.motion_prior_velocity_gain;
  velocity_ = velocity_ ? Eigen::Vector3d((1.0 - gain) * *velocity_ + gain * v) : v;
  if (options_.motion_prior_accel_lag_s <= 0.0) return;
  if (!recent_.empty() && !(frame.stamp > recent_.back().stamp)) recent_.clear();  // not a stretch
  recent_.push_back(frame);
  const double since = frame.stamp - options_.motion_prior_accel_window_s;
  recent_.erase(recent_.begin(), std::find_if(recent_.begin(), recent_.end(),
                                              [&](const SmootherSample& s) { return s.stamp >= since; }));
  measured_accel_ = measuredAccelSigma(recent_, 0, recent_.size(), options_.motion_prior_accel_lag_s);
}

void MotionPrior::reset() {
  velocity_.reset();
  recent_.clear();
  measured_accel_.reset();
}

double MotionPrior::accel() const {
  const double floor = options_.motion_prior_accel;
  if (options_.motion_prior_accel_lag_s <= 0.0) return floor;
  if (!measured_accel_) return std::max(floor, options_.motion_prior_accel_unmeasured);
  // A velocity smoothed at gain g lags a steadily accelerating camera by (1 - g) / g frames, so the
  // prediction misses by a dt^2 (1/2 + (1 - g) / g): the spread of a / 2 dt^2 for an a that much larger.
  const double g = options_.motion_prior_velocity_gain;
  return std::max(floor, *measured_accel_ * (1.0 + 2.0 * (1.0 - g) / g));
}

std::optional<PositionPrior> MotionPrior::predict(const Eigen::Vector3d& last_center, double dt) const {
  if (!velocity_ || options_.motion_prior_accel <= 0.0 || dt <= 0.0) return std::nullopt;
  // An unknown acceleration a moves the camera by a dt^2 / 2 from the constant-velocity path.
  return PositionPrior{last_center + *velocity_ * dt, 0.5 * accel() * dt * dt};
}

}  // namespace bmp::tracker

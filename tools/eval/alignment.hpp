#pragma once
// Horn's closed-form rigid alignment, written as evaluate_ate.py's align(): finds R, t minimising
// sum |R * model_i + t - data_i|^2 (no scale).
#include <Eigen/Core>

namespace bmp::eval {

struct RigidAlignment {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
  Eigen::Vector3d apply(const Eigen::Vector3d& p) const { return rotation * p + translation; }
};

// model and data are 3xN with matching columns, N >= 1.
RigidAlignment alignHorn(const Eigen::Matrix3Xd& model, const Eigen::Matrix3Xd& data);

}  // namespace bmp::eval

#pragma once
// A pose as Ceres optimises it (private to local bundle adjustment): T_cam_world as angle-axis (3), then
// translation (3).
#include "bmp/common/se3.hpp"

namespace bmp::tracker {

inline void poseToParams(const SE3& T, double* pose) {
  const Eigen::AngleAxisd aa(T.rotation());
  const Eigen::Vector3d w = aa.angle() * aa.axis();
  for (int i = 0; i < 3; ++i) {
    pose[i] = w[i];
    pose[3 + i] = T.translation()[i];
  }
}

inline SE3 poseFromParams(const double* pose) {
  const Eigen::Vector3d w(pose[0], pose[1], pose[2]);
  const double angle = w.norm();
  SE3 T = SE3::Identity();
  if (angle > 1e-12) T.linear() = Eigen::AngleAxisd(angle, w / angle).toRotationMatrix();
  T.translation() = Eigen::Vector3d(pose[3], pose[4], pose[5]);
  return T;
}

}  // namespace bmp::tracker

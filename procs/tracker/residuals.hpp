#pragma once
// Reprojection residuals for Ceres (private to local bundle adjustment). A pose is T_cam_world as angle-axis
// (3) then translation (3). With depth, the residual has a third row on the virtual right image, u - bf / z,
// so depth enters with the same pixel units and level-dependent variance as u and v.
#include <ceres/rotation.h>

#include <Eigen/Core>

namespace bmp::tracker {

struct PinholeBf {
  double fx = 0, fy = 0, cx = 0, cy = 0, bf = 0;
};

template <int kRows>
struct ReprojectionError {
  ReprojectionError(const PinholeBf& cam, const Eigen::Vector2d& uv, double u_right, double sqrt_info)
      : cam(cam), u(uv.x()), v(uv.y()), ur(u_right), s(sqrt_info) {}

  template <typename T>
  bool project(const T* pose, const T* p_world, T* r) const {
    T p_cam[3];
    ceres::AngleAxisRotatePoint(pose, p_world, p_cam);
    p_cam[0] += pose[3];
    p_cam[1] += pose[4];
    p_cam[2] += pose[5];
    const T inv_z = T(1.0) / p_cam[2];
    const T up = T(cam.fx) * p_cam[0] * inv_z + T(cam.cx);
    r[0] = T(s) * (up - T(u));
    r[1] = T(s) * (T(cam.fy) * p_cam[1] * inv_z + T(cam.cy) - T(v));
    if constexpr (kRows == 3) r[2] = T(s) * (up - T(cam.bf) * inv_z - T(ur));
    return true;
  }

  PinholeBf cam;
  double u, v, ur, s;
};

// Pose and point both free: bundle adjustment.
template <int kRows>
struct BundleError : ReprojectionError<kRows> {
  using ReprojectionError<kRows>::ReprojectionError;
  template <typename T>
  bool operator()(const T* pose, const T* p_world, T* r) const {
    return this->project(pose, p_world, r);
  }
};

}  // namespace bmp::tracker

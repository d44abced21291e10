#include "bmp/common/camera_model.hpp"

#include <cmath>

namespace bmp {

namespace {
// Ten fixed-point iterations bring the inverse distortion below 1e-6 px for the lenses we meet (|k1| < 0.3).
constexpr int kUndistortIterations = 10;
}  // namespace

CameraModel::CameraModel(const CameraIntrinsics& intrinsics) : k_(intrinsics) {
  distorted_ = false;
  for (double d : k_.distortion) distorted_ = distorted_ || d != 0.0;
}

Eigen::Vector2d CameraModel::distortNormalized(const Eigen::Vector2d& xy) const {
  if (!distorted_) return xy;
  const auto& d = k_.distortion;
  const double x = xy.x(), y = xy.y();
  const double r2 = x * x + y * y;
  const double radial = 1.0 + r2 * (d[0] + r2 * (d[1] + r2 * d[4]));
  const double xd = x * radial + 2.0 * d[2] * x * y + d[3] * (r2 + 2.0 * x * x);
  const double yd = y * radial + d[2] * (r2 + 2.0 * y * y) + 2.0 * d[3] * x * y;
  return {xd, yd};
}

Eigen::Vector2d CameraModel::undistortPixel(const Eigen::Vector2d& uv) const {
  if (!distorted_) return uv;
  const Eigen::Vector2d xd((uv.x() - k_.cx) / k_.fx, (uv.y() - k_.cy) / k_.fy);
  Eigen::Vector2d xy = xd;
  for (int i = 0; i < kUndistortIterations; ++i) {
    const Eigen::Vector2d error = distortNormalized(xy) - xd;
    xy -= error;
  }
  return {xy.x() * k_.fx + k_.cx, xy.y() * k_.fy + k_.cy};
}

Eigen::Vector2d CameraModel::projectPinhole(const Eigen::Vector3d& p_cam) const {
  return {k_.fx * p_cam.x() / p_cam.z() + k_.cx, k_.fy * p_cam.y() / p_cam.z() + k_.cy};
}

Eigen::Vector2d CameraModel::project(const Eigen::Vector3d& p_cam) const {
  const Eigen::Vector2d xy = distortNormalized({p_cam.x() / p_cam.z(), p_cam.y() / p_cam.z()});
  return {k_.fx * xy.x() + k_.cx, k_.fy * xy.y() + k_.cy};
}

Eigen::Vector3d CameraModel::backProject(const Eigen::Vector2d& uv, double depth) const {
  return {(uv.x() - k_.cx) / k_.fx * depth, (uv.y() - k_.cy) / k_.fy * depth, depth};
}

bool CameraModel::inImage(const Eigen::Vector2d& uv, double border) const {
  return uv.x() >= border && uv.y() >= border && uv.x() < k_.width - border && uv.y() < k_.height - border;
}

}  // namespace bmp

#include "bmp/common/camera_model.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include <Eigen/LU>

namespace bmp {

namespace {
// Newton's method on the distortion reaches machine precision in 3-6 steps for real lenses; the plain
// fixed-point iteration used before was off by 0.03 px at the corners for k1 = -0.2 and diverged for k1 = 1.
constexpr int kUndistortMaxSteps = 20;
constexpr double kUndistortStepDone = 1e-12;  // normalised units: a step this small has converged
constexpr double kUndistortTolerancePx = 1e-3;
// Border pixels tested by undistortionProblem: dense enough for any plumb-bob lens's fold to show.
constexpr int kBorderStepPx = 16;
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

Eigen::Matrix2d CameraModel::distortionJacobian(const Eigen::Vector2d& xy) const {
  const auto& d = k_.distortion;
  const double x = xy.x(), y = xy.y();
  const double r2 = x * x + y * y;
  const double radial = 1.0 + r2 * (d[0] + r2 * (d[1] + r2 * d[4]));
  const double dradial_dr2 = d[0] + r2 * (2.0 * d[1] + 3.0 * r2 * d[4]);
  const double cross = 2.0 * x * y * dradial_dr2 + 2.0 * d[2] * x + 2.0 * d[3] * y;
  Eigen::Matrix2d J;
  J << radial + 2.0 * x * x * dradial_dr2 + 2.0 * d[2] * y + 6.0 * d[3] * x, cross,  //
      cross, radial + 2.0 * y * y * dradial_dr2 + 6.0 * d[2] * y + 2.0 * d[3] * x;
  return J;
}

Eigen::Vector2d CameraModel::undistortPixel(const Eigen::Vector2d& uv) const {
  if (!distorted_) return uv;
  const Eigen::Vector2d xd((uv.x() - k_.cx) / k_.fx, (uv.y() - k_.cy) / k_.fy);
  Eigen::Vector2d xy = xd;
  for (int i = 0; i < kUndistortMaxSteps; ++i) {
    const Eigen::Vector2d step = distortionJacobian(xy).inverse() * (distortNormalized(xy) - xd);
    if (!step.allFinite()) break;
    xy -= step;
    if (step.norm() < kUndistortStepDone) break;
  }
  // Beyond a lens model's fold (its Jacobian no longer orientation-preserving) no undistorted point maps
  // here, or only one on the wrong branch: not a ray of this camera.
  const Eigen::Vector2d error = distortNormalized(xy) - xd;
  const bool converged = xy.allFinite() && std::abs(error.x() * k_.fx) < kUndistortTolerancePx &&
                         std::abs(error.y() * k_.fy) < kUndistortTolerancePx &&
                         distortionJacobian(xy).determinant() > 0.0;
  if (!converged) return {std::nan(""), std::nan("")};
  return {xy.x() * k_.fx + k_.cx, xy.y() * k_.fy + k_.cy};
}

std::string imageSizeProblem(long long width, long long height) {
  const std::string size = std::to_string(width) + "x" + std::to_string(height);
  if (width <= 0 || height <= 0 || width > kMaxImageSide || height > kMaxImageSide)
    return size + " is not a camera's (sides 1 to " + std::to_string(kMaxImageSide) + " pixels)";
  if (width * height > kMaxImagePixels)
    return size + " is not a camera's (at most " + std::to_string(kMaxImagePixels) + " pixels)";
  return "";
}

std::string focalLengthProblem(const CameraIntrinsics& k) {
  if (!std::isfinite(k.fx) || !std::isfinite(k.fy) || k.fx <= 0 || k.fy <= 0)
    return "focal length fx/fy must be positive";
  const auto fits = [](double f, int side) {
    return f >= kMinFocalPerSide * side && f <= kMaxFocalPerSide * side;
  };
  if (!fits(k.fx, k.width) || !fits(k.fy, k.height)) {
    std::ostringstream why;
    why << "focal length fx " << k.fx << ", fy " << k.fy << " is not a camera's for a " << k.width << "x"
        << k.height << " image (" << kMinFocalPerSide << " to " << kMaxFocalPerSide << " times its side)";
    return why.str();
  }
  return "";
}

std::string intrinsicsProblem(const CameraIntrinsics& k) {
  if (std::string why = imageSizeProblem(k.width, k.height); !why.empty()) return "camera size " + why;
  for (double v : {k.fx, k.fy, k.cx, k.cy})
    if (!std::isfinite(v)) return "camera intrinsics are not finite";
  if (std::string why = focalLengthProblem(k); !why.empty()) return "camera " + why;
  if (k.cx < 0 || k.cy < 0 || k.cx > k.width || k.cy > k.height)
    return "camera principal point lies outside the image";
  for (double d : k.distortion) {
    if (!std::isfinite(d)) return "camera distortion is not finite";
    if (std::abs(d) > kMaxDistortionCoefficient)
      return "camera distortion coefficient " + std::to_string(d) +
             " is not a lens's (|k| <= " + std::to_string(static_cast<int>(kMaxDistortionCoefficient)) + ")";
  }
  if (!std::isfinite(k.depth_scale) || k.depth_scale <= 0) return "depth_scale must be positive";
  if (std::string why = undistortionProblem(k); !why.empty()) return "camera: " + why;
  return "";
}

std::string undistortionProblem(const CameraIntrinsics& k) {
  const CameraModel model(k);
  if (!model.hasDistortion()) return "";
  const auto check = [&](int u, int v) -> std::string {
    if (model.undistortPixel(Eigen::Vector2d(u, v)).allFinite()) return "";
    return "the lens distortion cannot be undone at pixel (" + std::to_string(u) + ", " + std::to_string(v) +
           ") of the " + std::to_string(k.width) + "x" + std::to_string(k.height) +
           " image (the model folds over inside the image: not a real lens's calibration)";
  };
  for (int u = 0;; u = std::min(u + kBorderStepPx, k.width)) {
    for (const int v : {0, k.height})
      if (std::string why = check(u, v); !why.empty()) return why;
    if (u == k.width) break;
  }
  for (int v = 0;; v = std::min(v + kBorderStepPx, k.height)) {
    for (const int u : {0, k.width})
      if (std::string why = check(u, v); !why.empty()) return why;
    if (v == k.height) break;
  }
  return "";
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

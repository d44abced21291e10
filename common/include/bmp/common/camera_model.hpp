#pragma once
// Pinhole camera with radial-tangential distortion (OpenCV's plumb-bob model: k1, k2, p1, p2, k3).
#include <array>
#include <string>

#include <Eigen/Core>

namespace bmp {

struct CameraIntrinsics {
  int width = 640;
  int height = 480;
  double fx = 525.0;
  double fy = 525.0;
  double cx = 319.5;
  double cy = 239.5;
  std::array<double, 5> distortion{0, 0, 0, 0, 0};  // k1, k2, p1, p2, k3
  double depth_scale = 5000.0;                      // raw depth units per metre
};

// The largest |coefficient| accepted in the distortion model: real lenses stay within a few units (wide
// angles included); under much larger ones undistortion diverges to infinity.
constexpr double kMaxDistortionCoefficient = 10.0;
// The largest image side we accept (a camera file's or a frame's): larger is a mistake, not a camera we
// support, and would overflow pixel arithmetic (undistortionProblem walks the border).
inline constexpr int kMaxImageSide = 8192;

// "" when the lens distortion can be undone over the whole image (tested along its border, where the
// distortion is largest); else which pixel it cannot and why. Expects finite intrinsics with fx, fy > 0.
std::string undistortionProblem(const CameraIntrinsics& k);

class CameraModel {
 public:
  explicit CameraModel(const CameraIntrinsics& intrinsics);

  const CameraIntrinsics& intrinsics() const { return k_; }
  bool hasDistortion() const { return distorted_; }

  // Normalised undistorted coordinates -> distorted pixel.
  Eigen::Vector2d distortNormalized(const Eigen::Vector2d& xy) const;
  // d distortNormalized / d xy.
  Eigen::Matrix2d distortionJacobian(const Eigen::Vector2d& xy) const;
  // Distorted pixel -> undistorted pixel (Newton's method on the distortion). NaN where the distortion
  // cannot be undone to within a thousandth of a pixel (beyond the model's fold).
  Eigen::Vector2d undistortPixel(const Eigen::Vector2d& uv) const;
  // A point in the camera frame (z forward) -> distorted pixel. z must be positive.
  Eigen::Vector2d project(const Eigen::Vector3d& p_cam) const;
  // Ideal (undistorted) pinhole projection.
  Eigen::Vector2d projectPinhole(const Eigen::Vector3d& p_cam) const;
  // An undistorted pixel and depth (metres) -> point in the camera frame.
  Eigen::Vector3d backProject(const Eigen::Vector2d& uv_undistorted, double depth) const;
  bool inImage(const Eigen::Vector2d& uv, double border = 0.0) const;

 private:
  CameraIntrinsics k_;
  bool distorted_;
};

}  // namespace bmp

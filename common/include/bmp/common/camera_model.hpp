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
// The largest image in pixels: 16 MP holds any RGB-D camera's colour (Azure Kinect's 4096x3072 is 12.6 MP).
// An 8192x8192 frame cost the detector 200 MB and 2.7 s to decode, and the mapper 4.9 GB and 41 s, before
// its camera could be refused as not the stream's.
inline constexpr long long kMaxImagePixels = 4096LL * 4096;
// Focal lengths in pixels relative to the image side: under 0.04 is a view wider than 170 degrees, over 100
// narrower than 0.6; neither is an RGB-D camera's, and fx = 1e-20 put points 1e22 m away.
inline constexpr double kMinFocalPerSide = 0.04;
inline constexpr double kMaxFocalPerSide = 100.0;

// "" when width x height is an image size we accept; else why ("WxH is not ...").
std::string imageSizeProblem(long long width, long long height);
// "" when fx and fy are finite, positive and fit the image's width and height (kMin/kMaxFocalPerSide); else
// why. Expects a size imageSizeProblem accepts.
std::string focalLengthProblem(const CameraIntrinsics& k);

// "" when k is a camera a frame or keyframe may come with: its size, finite intrinsics, focal lengths, a
// principal point inside the image, a lens's distortion that can be undone, a positive depth scale; else
// why, naming the camera ("camera principal point lies outside the image"). The frame stream's and the
// mapper's checks, one rule set; a camera file is checked key by key (camera_config.hpp).
std::string intrinsicsProblem(const CameraIntrinsics& k);

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

#pragma once
// Undistorted viewing rays of every pixel of one camera, computed once: undistortion is iterative, too
// slow to repeat for 300,000 pixels per keyframe.
#include <opencv2/core.hpp>

#include "bmp/common/camera_model.hpp"

namespace bmp::mapper {

class RayTable {
 public:
  RayTable() = default;
  explicit RayTable(const CameraIntrinsics& camera);
  // True when the table was built for these intrinsics (depth scale aside).
  bool fits(const CameraIntrinsics& camera) const;
  // Normalised coordinates (x/z, y/z) of pixel (u, v)'s ray.
  const cv::Vec2f& ray(int u, int v) const { return rays_.at<cv::Vec2f>(v, u); }

 private:
  CameraIntrinsics camera_;
  cv::Mat rays_;  // CV_32FC2
};

}  // namespace bmp::mapper

#pragma once
// Keyframes for mapper tests, made by hand: a flat wall facing the camera, optionally with a patch nearer.
#include <cstdint>

#include <opencv2/core.hpp>

#include "mapper/keyframe_input.hpp"
#include "mapper/mapper_settings.hpp"

namespace bmp::mapper::test {

inline CameraIntrinsics smallCamera() {
  CameraIntrinsics k;
  k.width = 160;
  k.height = 120;
  k.fx = k.fy = 131.25;  // the 640x480 camera's field of view at a quarter of its size
  k.cx = 79.5;
  k.cy = 59.5;
  k.depth_scale = 5000.0;
  return k;
}

// A wall at depth_m filling the view; a patch (x, y, w, h pixels) at patch_depth_m when given.
inline KeyframeInput wallKeyframe(int64_t id, const SE3& T_world_cam, double depth_m,
                                  const cv::Rect& patch = cv::Rect(), double patch_depth_m = 0.0) {
  KeyframeInput kf;
  kf.id = id;
  kf.stamp = static_cast<double>(id);
  kf.T_world_cam = T_world_cam;
  kf.camera = smallCamera();
  kf.color = cv::Mat(kf.camera.height, kf.camera.width, CV_8UC3, cv::Scalar(40, 120, 200));
  kf.depth = cv::Mat(kf.camera.height, kf.camera.width, CV_16UC1,
                     cv::Scalar(static_cast<int>(depth_m * kf.camera.depth_scale)));
  if (patch.area() > 0) kf.depth(patch).setTo(static_cast<int>(patch_depth_m * kf.camera.depth_scale));
  kf.dynamic_mask = cv::Mat::zeros(kf.camera.height, kf.camera.width, CV_8UC1);
  return kf;
}

// Settings for small hand-made scenes: rebuilds whenever asked, the world's up is the camera's -y.
inline MapperSettings testSettings() {
  MapperSettings s;
  s.rebuild.min_interval_s = 5.0;
  s.cloud.max_depth_m = 6.0;
  s.octomap.max_range_m = 6.0;
  // The scenes here are walls in front of the camera, no floor: a fixed one 1 m below the camera, the band
  // up to 0.5 m above the camera.
  s.grid.floor.mode = FloorMode::kFixed;
  s.grid.floor.height_m = -1.0;
  s.grid.height_min_m = 0.0;
  s.grid.height_max_m = 1.5;
  return s;
}

inline SE3 translation(double x, double y, double z) {
  SE3 T = SE3::Identity();
  T.translation() = Eigen::Vector3d(x, y, z);
  return T;
}

}  // namespace bmp::mapper::test

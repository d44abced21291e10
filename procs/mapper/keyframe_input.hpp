#pragma once
// A keyframe as the mapper takes it: decoded images, its pose and its camera.
#include <cstdint>
#include <string>

#include <opencv2/core.hpp>

#include "bmp/common/camera_model.hpp"
#include "bmp/common/se3.hpp"

namespace bmp::mapper {

struct KeyframeInput {
  int64_t id = 0;
  double stamp = 0.0;  // seconds
  SE3 T_world_cam = SE3::Identity();
  CameraIntrinsics camera;  // depth_scale: raw depth units per metre
  cv::Mat color;            // CV_8UC3, camera size
  cv::Mat depth;            // CV_16UC1, camera size, 0 = no measurement
  cv::Mat dynamic_mask;     // CV_8UC1, camera size, non-zero on moving objects; empty = nothing masked
};

// Why the keyframe cannot be mapped (non-finite or impossible intrinsics or pose, images of the wrong type
// or size), or "" when it can.
std::string checkKeyframe(const KeyframeInput& kf);
// Why a keyframe whose camera and declared image sizes these are cannot be mapped, or "": checked before its
// images are decoded, since a few hostile bytes of PNG can declare a picture of gigabytes.
std::string checkKeyframeHeader(const CameraIntrinsics& camera, const cv::Size& depth, const cv::Size& color,
                                const cv::Size& mask);
// Why a pose cannot be used (non-finite, rotation not orthonormal), or "".
std::string checkPose(const SE3& T);

}  // namespace bmp::mapper

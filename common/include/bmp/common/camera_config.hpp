#pragma once
// Camera intrinsics from a configuration section (config/cameras/*.yaml, key "camera").
#include "bmp/common/camera_model.hpp"
#include "bmp/common/config.hpp"

namespace bmp {

// Reads width, height, fx, fy, cx, cy, distortion (5 values) and depth_scale; all required.
CameraIntrinsics cameraFromConfig(const Config& camera_section);

}  // namespace bmp

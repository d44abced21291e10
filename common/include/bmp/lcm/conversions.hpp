#pragma once
// Between LCM messages and the library types of common/.
#include <bmp/camera_t.hpp>
#include <bmp/image_t.hpp>
#include <bmp/pose_t.hpp>

#include <string>

#include "bmp/common/camera_model.hpp"
#include "bmp/common/image_codec.hpp"
#include "bmp/common/se3.hpp"

namespace bmp {

pose_t toMsg(const SE3& T);
SE3 fromMsg(const pose_t& msg);  // normalises the quaternion
// Why a pose from another process cannot be used ("" when it can): not finite, or its quaternion not a
// unit one as sent (normalising a forged (0, 0, 0, 0) would invent a rotation).
std::string checkPoseMessage(const pose_t& msg);

camera_t toMsg(const CameraIntrinsics& k);
// depth_scale is not part of camera_t: it travels beside it in the frame.
CameraIntrinsics fromMsg(const camera_t& msg, double depth_scale);

image_t toMsg(const EncodedImage& image);
image_t toMsg(EncodedImage&& image);
// Throws ImageError when the message's encoding or pixel format is not one we know.
EncodedImage fromMsg(const image_t& msg);

}  // namespace bmp

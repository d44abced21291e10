#include "bmp/lcm/conversions.hpp"

#include <cmath>

namespace bmp {

pose_t toMsg(const SE3& T) {
  pose_t msg;
  const Eigen::Quaterniond q(T.linear());
  for (int i = 0; i < 3; ++i) msg.position[i] = T.translation()[i];
  msg.orientation[0] = q.w();
  msg.orientation[1] = q.x();
  msg.orientation[2] = q.y();
  msg.orientation[3] = q.z();
  return msg;
}

SE3 fromMsg(const pose_t& msg) {
  const Eigen::Quaterniond q(msg.orientation[0], msg.orientation[1], msg.orientation[2], msg.orientation[3]);
  return makeSE3({msg.position[0], msg.position[1], msg.position[2]}, q);
}

std::string checkPoseMessage(const pose_t& msg) {
  double norm2 = 0;
  for (double q : msg.orientation) norm2 += q * q;
  bool finite = std::isfinite(norm2);
  for (double t : msg.position) finite = finite && std::isfinite(t);
  if (!finite) return "non-finite pose";
  if (std::abs(std::sqrt(norm2) - 1.0) > 1e-3) return "pose quaternion is not a unit quaternion";
  return "";
}

camera_t toMsg(const CameraIntrinsics& k) {
  camera_t msg;
  msg.width = k.width;
  msg.height = k.height;
  msg.fx = k.fx;
  msg.fy = k.fy;
  msg.cx = k.cx;
  msg.cy = k.cy;
  for (int i = 0; i < 5; ++i) msg.distortion[i] = k.distortion[i];
  return msg;
}

CameraIntrinsics fromMsg(const camera_t& msg, double depth_scale) {
  CameraIntrinsics k;
  k.width = msg.width;
  k.height = msg.height;
  k.fx = msg.fx;
  k.fy = msg.fy;
  k.cx = msg.cx;
  k.cy = msg.cy;
  for (int i = 0; i < 5; ++i) k.distortion[i] = msg.distortion[i];
  k.depth_scale = depth_scale;
  return k;
}

namespace {
image_t header(const EncodedImage& image) {
  image_t msg;
  msg.width = image.width;
  msg.height = image.height;
  msg.encoding = static_cast<int8_t>(image.encoding);
  msg.pixel_format = static_cast<int8_t>(image.pixel_format);
  msg.size = static_cast<int32_t>(image.data.size());
  return msg;
}
}  // namespace

image_t toMsg(const EncodedImage& image) {
  image_t msg = header(image);
  msg.data = image.data;
  return msg;
}

image_t toMsg(EncodedImage&& image) {
  image_t msg = header(image);
  msg.data = std::move(image.data);
  return msg;
}

EncodedImage fromMsg(const image_t& msg) {
  if (msg.encoding < 0 || msg.encoding > 2)
    throw ImageError("unknown image encoding " + std::to_string(msg.encoding));
  if (msg.pixel_format < 0 || msg.pixel_format > 2)
    throw ImageError("unknown pixel format " + std::to_string(msg.pixel_format));
  EncodedImage image;
  image.width = msg.width;
  image.height = msg.height;
  image.encoding = static_cast<ImageEncoding>(msg.encoding);
  image.pixel_format = static_cast<PixelFormat>(msg.pixel_format);
  image.data = msg.data;
  return image;
}

}  // namespace bmp

#include "mapper/keyframe_input.hpp"

#include <cmath>

namespace bmp::mapper {

namespace {

std::string checkSize(const cv::Size& size, const CameraIntrinsics& k, const char* what) {
  if (size.width != k.width || size.height != k.height)
    return std::string(what) + " is " + std::to_string(size.width) + "x" + std::to_string(size.height) +
           ", camera is " + std::to_string(k.width) + "x" + std::to_string(k.height);
  return "";
}

std::string checkImage(const cv::Mat& m, int type, const CameraIntrinsics& k, const char* what) {
  if (m.type() != type) return std::string(what) + " has the wrong pixel type";
  return checkSize(m.size(), k, what);
}

}  // namespace

std::string checkPose(const SE3& T) {
  if (!T.matrix().allFinite()) return "non-finite pose";
  const Eigen::Matrix3d R = T.linear();
  if ((R * R.transpose() - Eigen::Matrix3d::Identity()).norm() > 1e-3 || R.determinant() < 0)
    return "pose rotation is not a rotation";
  return "";
}

std::string checkKeyframeHeader(const CameraIntrinsics& camera, const cv::Size& depth, const cv::Size& color,
                                const cv::Size& mask) {
  std::string why = intrinsicsProblem(camera);
  if (why.empty()) why = checkSize(depth, camera, "depth");
  if (why.empty()) why = checkSize(color, camera, "colour");
  if (why.empty() && !mask.empty()) why = checkSize(mask, camera, "mask");
  return why;
}

std::string checkKeyframe(const KeyframeInput& kf) {
  std::string why = intrinsicsProblem(kf.camera);
  if (why.empty()) why = checkPose(kf.T_world_cam);
  if (why.empty()) why = checkImage(kf.depth, CV_16UC1, kf.camera, "depth");
  if (why.empty()) why = checkImage(kf.color, CV_8UC3, kf.camera, "colour");
  if (why.empty() && !kf.dynamic_mask.empty()) why = checkImage(kf.dynamic_mask, CV_8UC1, kf.camera, "mask");
  return why;
}

}  // namespace bmp::mapper

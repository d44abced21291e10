#include "tracker/lcm/tracker_messages.hpp"

#include <cmath>

#include "bmp/lcm/conversions.hpp"

namespace bmp::tracker {

static_assert(static_cast<int>(TrackingState::kInitialising) == slam_pose_t::STATE_INITIALISING &&
              static_cast<int>(TrackingState::kOk) == slam_pose_t::STATE_OK &&
              static_cast<int>(TrackingState::kLost) == slam_pose_t::STATE_LOST &&
              static_cast<int>(TrackingState::kRelocalised) == slam_pose_t::STATE_RELOCALISED);

namespace {

// A message's image as it travels, re-encoded only when it arrived raw.
image_t forwardOrEncode(const image_t& msg, const cv::Mat& decoded, ImageEncoding encoding) {
  if (msg.encoding != static_cast<int8_t>(ImageEncoding::kRaw)) return msg;
  return toMsg(encodeImage(decoded, encoding));
}

}  // namespace

slam_pose_t toPoseMessage(const rgbd_frame_t& frame, const TrackResult& r) {
  slam_pose_t out;
  out.utime = frame.utime;
  out.seq = frame.seq;
  out.T_world_cam = toMsg(r.T_world_cam);
  out.state = static_cast<int8_t>(r.state);
  out.num_keypoints = r.num_keypoints;
  out.num_tracked = r.num_tracked;
  out.num_dynamic = r.num_excluded + r.num_dynamic;
  out.num_map_points = r.num_map_points;
  out.reference_keyframe_id = r.reference_keyframe_id;
  out.processing_ms = static_cast<float>(r.processing_ms);
  out.position_std_m = std::isfinite(r.position_std_m) ? static_cast<float>(r.position_std_m) : -1.0f;
  return out;
}

slam_pose_t toSkippedPoseMessage(const rgbd_frame_t& frame, const std::string& reason) {
  slam_pose_t out{};
  out.note = reason;
  out.utime = frame.utime;
  out.seq = frame.seq;
  out.T_world_cam = toMsg(SE3::Identity());
  out.state = slam_pose_t::STATE_SKIPPED;
  out.reference_keyframe_id = -1;
  out.position_std_m = -1.0f;
  return out;
}

keyframe_t toKeyFrameMessage(const rgbd_frame_t& frame, const cv::Mat& color, const cv::Mat& depth,
                             const KeyFramePose& kf, const cv::Mat& dynamic_mask) {
  keyframe_t out;
  out.utime = frame.utime;
  out.id = kf.id;
  out.seq = frame.seq;
  out.T_world_cam = toMsg(kf.T_world_cam);
  out.camera = frame.camera;
  out.depth_scale = frame.depth_scale;
  out.color = forwardOrEncode(frame.color, color, ImageEncoding::kJpeg);
  out.depth = forwardOrEncode(frame.depth, depth, ImageEncoding::kPng);
  out.dynamic_mask = toMsg(encodeImage(dynamic_mask, ImageEncoding::kPng));
  return out;
}

keyframe_poses_t toKeyFramePosesMessage(int64_t utime, const std::vector<KeyFramePose>& updates) {
  keyframe_poses_t out;
  out.utime = utime;
  out.num_keyframes = static_cast<int32_t>(updates.size());
  for (const auto& u : updates) {
    out.ids.push_back(u.id);
    out.T_world_cam.push_back(toMsg(u.T_world_cam));
  }
  return out;
}

}  // namespace bmp::tracker

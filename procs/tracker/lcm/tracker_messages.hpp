#pragma once
// The tracker's outgoing contracts (lcmtypes/slam_pose_t, keyframe_t, keyframe_poses_t) from its results.
#include <string>
#include <vector>

#include <bmp/keyframe_poses_t.hpp>
#include <bmp/keyframe_t.hpp>
#include <bmp/rgbd_frame_t.hpp>
#include <bmp/slam_pose_t.hpp>
#include <opencv2/core.hpp>

#include "tracker/local_mapper.hpp"
#include "tracker/tracker.hpp"

namespace bmp::tracker {

// The pose answering one frame (and acknowledging it in lockstep): the frame's utime and seq.
slam_pose_t toPoseMessage(const rgbd_frame_t& frame, const TrackResult& result);
// The answer for a frame the tracker could not use: STATE_SKIPPED with the reason, so lockstep does not
// wait in vain and whoever listens learns why.
slam_pose_t toSkippedPoseMessage(const rgbd_frame_t& frame, const std::string& reason);

// A new keyframe with the frame's colour and depth as they travelled (file bytes forwarded untouched; raw
// images are encoded: colour JPEG, depth PNG) and a mono8 PNG dynamic mask of the colour image's size.
keyframe_t toKeyFrameMessage(const rgbd_frame_t& frame, const cv::Mat& color, const cv::Mat& depth,
                             const KeyFramePose& keyframe, const cv::Mat& dynamic_mask);

keyframe_poses_t toKeyFramePosesMessage(int64_t utime, const std::vector<KeyFramePose>& updates);

}  // namespace bmp::tracker

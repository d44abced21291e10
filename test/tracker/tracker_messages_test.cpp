// The tracker's outgoing messages from its results: the pose answers the frame it came from (lockstep
// depends on utime and seq), keyframes carry the images as they travelled or, when raw, encoded losslessly
// enough to use, and pose updates keep ids and poses paired.
#include <gtest/gtest.h>

#include "bmp/common/image_codec.hpp"
#include "bmp/lcm/conversions.hpp"
#include "tracker/lcm/tracker_messages.hpp"

namespace bmp::tracker {
namespace {

rgbd_frame_t frameMessage(const cv::Mat& color, const cv::Mat& depth, bool encoded) {
  rgbd_frame_t f{};
  f.utime = 1548339829896440;
  f.seq = 12;
  f.depth_scale = 5000.0;
  f.camera.width = color.cols;
  f.camera.height = color.rows;
  f.camera.fx = 542.8;
  f.camera.fy = 542.6;
  f.camera.cx = 315.6;
  f.camera.cy = 237.8;
  f.color = toMsg(encodeImage(color, encoded ? ImageEncoding::kJpeg : ImageEncoding::kRaw));
  f.depth = toMsg(encodeImage(depth, encoded ? ImageEncoding::kPng : ImageEncoding::kRaw));
  return f;
}

struct Images {
  cv::Mat color, depth;
  Images() : color(48, 64, CV_8UC3), depth(48, 64, CV_16UC1) {
    cv::randu(color, 0, 255);
    for (int v = 0; v < depth.rows; ++v)
      for (int u = 0; u < depth.cols; ++u)
        depth.at<uint16_t>(v, u) = static_cast<uint16_t>(5000 + 37 * u + v);
  }
};

TEST(TrackerMessages, PoseAnswersItsFrameWithStateAndCounts) {
  const Images im;
  const rgbd_frame_t frame = frameMessage(im.color, im.depth, true);
  TrackResult r;
  r.state = TrackingState::kRelocalised;
  r.T_world_cam =
      makeSE3({0.5, -1.0, 2.0}, Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitY())));
  r.num_keypoints = 1000;
  r.num_tracked = 420;
  r.num_excluded = 35;
  r.num_map_points = 9000;
  r.reference_keyframe_id = 7;
  r.processing_ms = 9.5;
  r.position_std_m = 0.0042;
  const slam_pose_t p = toPoseMessage(frame, r);
  EXPECT_EQ(p.utime, frame.utime);
  EXPECT_EQ(p.seq, 12);
  EXPECT_EQ(p.state, +slam_pose_t::STATE_RELOCALISED);
  EXPECT_EQ(p.num_keypoints, 1000);
  EXPECT_EQ(p.num_tracked, 420);
  EXPECT_EQ(p.num_dynamic, 35);
  EXPECT_EQ(p.num_map_points, 9000);
  EXPECT_EQ(p.reference_keyframe_id, 7);
  EXPECT_FLOAT_EQ(p.processing_ms, 9.5f);
  EXPECT_FLOAT_EQ(p.position_std_m, 0.0042f);
  EXPECT_LT((fromMsg(p.T_world_cam).matrix() - r.T_world_cam.matrix()).norm(), 1e-9);
}

TEST(TrackerMessages, SkippedFrameIsAnsweredWithItsSeq) {
  const Images im;
  const slam_pose_t p =
      toSkippedPoseMessage(frameMessage(im.color, im.depth, true), "colour image: not a PNG");
  EXPECT_EQ(p.seq, 12);
  EXPECT_EQ(p.utime, 1548339829896440);
  EXPECT_EQ(p.state, +slam_pose_t::STATE_SKIPPED);
  EXPECT_EQ(p.reference_keyframe_id, -1);
  EXPECT_EQ(p.note, "colour image: not a PNG");
  EXPECT_EQ(p.position_std_m, -1.0f);
}

TEST(TrackerMessages, AFrameNotTrackedHasNoPositionStd) {
  const Images im;
  TrackResult lost;
  lost.state = TrackingState::kLost;  // position_std_m stays infinite
  EXPECT_EQ(toPoseMessage(frameMessage(im.color, im.depth, true), lost).position_std_m, -1.0f);
}

TEST(TrackerMessages, KeyFrameForwardsFileBytesUntouched) {
  const Images im;
  const rgbd_frame_t frame = frameMessage(im.color, im.depth, true);
  KeyFramePose kf{3, 1548339829.89644, SE3::Identity()};
  const cv::Mat mask = cv::Mat::zeros(im.color.size(), CV_8UC1);
  const keyframe_t k = toKeyFrameMessage(frame, im.color, im.depth, kf, mask);
  EXPECT_EQ(k.id, 3);
  EXPECT_EQ(k.seq, 12);
  EXPECT_EQ(k.utime, frame.utime);
  EXPECT_EQ(k.camera.fx, frame.camera.fx);
  EXPECT_EQ(k.depth_scale, 5000.0);
  EXPECT_EQ(k.color.data, frame.color.data);  // the JPEG as captured, not re-encoded
  EXPECT_EQ(k.depth.data, frame.depth.data);
  const cv::Mat m = decodeImage(fromMsg(k.dynamic_mask));
  ASSERT_EQ(m.type(), CV_8UC1);
  EXPECT_EQ(m.size(), im.color.size());
  EXPECT_EQ(cv::countNonZero(m), 0);
}

TEST(TrackerMessages, KeyFrameEncodesRawImagesDepthExactly) {
  const Images im;
  const rgbd_frame_t frame = frameMessage(im.color, im.depth, false);
  cv::Mat mask = cv::Mat::zeros(im.color.size(), CV_8UC1);
  mask(cv::Rect(10, 5, 20, 30)).setTo(255);
  const keyframe_t k = toKeyFrameMessage(frame, im.color, im.depth, KeyFramePose{}, mask);
  EXPECT_EQ(k.color.encoding, static_cast<int8_t>(ImageEncoding::kJpeg));
  EXPECT_EQ(k.depth.encoding, static_cast<int8_t>(ImageEncoding::kPng));
  const cv::Mat depth = decodeImage(fromMsg(k.depth));
  ASSERT_EQ(depth.type(), CV_16UC1);
  EXPECT_EQ(cv::norm(depth, im.depth, cv::NORM_INF), 0.0);  // PNG: depth survives exactly
  const cv::Mat color = decodeImage(fromMsg(k.color));
  EXPECT_EQ(color.size(), im.color.size());
  EXPECT_EQ(cv::countNonZero(decodeImage(fromMsg(k.dynamic_mask))), 20 * 30);
}

TEST(TrackerMessages, KeyFramePoseUpdatesKeepIdsAndPosesPaired) {
  std::vector<KeyFramePose> updates;
  for (int i = 0; i < 3; ++i)
    updates.push_back({10 + i, 0.0, makeSE3({double(i), 0, 0}, Eigen::Quaterniond::Identity())});
  const keyframe_poses_t m = toKeyFramePosesMessage(77, updates);
  EXPECT_EQ(m.utime, 77);
  ASSERT_EQ(m.num_keyframes, 3);
  ASSERT_EQ(m.ids.size(), 3u);
  ASSERT_EQ(m.T_world_cam.size(), 3u);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(m.ids[i], 10 + i);
    EXPECT_NEAR(fromMsg(m.T_world_cam[i]).translation().x(), i, 1e-12);
  }
}

}  // namespace
}  // namespace bmp::tracker

// Untrusted keyframe_t and keyframe_poses_t content: what decodes becomes library input; a PNG that does not
// decode, a mask or depth of the wrong size, non-finite pose or intrinsics is refused with its reason.
#include <gtest/gtest.h>

#include <limits>

#include "bmp/lcm/conversions.hpp"
#include "keyframe_message_util.hpp"
#include "mapper/lcm/mapper_messages.hpp"
#include "mapper_test_util.hpp"

namespace bmp::mapper {
namespace {

using test::keyframeMessage;

keyframe_t good() {
  return keyframeMessage(test::wallKeyframe(5, test::translation(0.1, 0.2, 0.3), 2.0));
}

std::string reasonOf(const keyframe_t& m) {
  KeyframeInput kf;
  return keyframeFromMessage(m, kf);
}

TEST(MapperMessages, GoodKeyframeDecodes) {
  KeyframeInput kf;
  ASSERT_EQ(keyframeFromMessage(good(), kf), "");
  EXPECT_EQ(kf.id, 5);
  EXPECT_EQ(kf.depth.type(), CV_16UC1);
  EXPECT_EQ(kf.depth.at<uint16_t>(3, 3), 10000);
  EXPECT_NEAR(kf.T_world_cam.translation().y(), 0.2, 1e-12);
  EXPECT_DOUBLE_EQ(kf.camera.depth_scale, 5000.0);
}

TEST(MapperMessages, CorruptDepthPng) {
  keyframe_t m = good();
  for (std::size_t i = 40; i < m.depth.data.size(); ++i) m.depth.data[i] = 0x5a;
  EXPECT_NE(reasonOf(m).find("depth does not decode"), std::string::npos) << reasonOf(m);
}

TEST(MapperMessages, WrongSizes) {
  keyframe_t m = good();
  m.dynamic_mask = toMsg(encodeImage(cv::Mat::zeros(60, 80, CV_8UC1), ImageEncoding::kPng));
  EXPECT_NE(reasonOf(m).find("mask is 80x60"), std::string::npos) << reasonOf(m);
  m = good();
  m.depth = toMsg(encodeImage(cv::Mat::zeros(60, 80, CV_16UC1), ImageEncoding::kPng));
  EXPECT_NE(reasonOf(m).find("depth is 80x60"), std::string::npos) << reasonOf(m);
}

// A PNG that declares a picture larger than the camera's is refused before it is decoded: a few hundred KB
// of zeros can declare gigabytes of pixels.
TEST(MapperMessages, AnImageLargerThanTheCameraIsRefusedUndecoded) {
  keyframe_t m = good();
  m.depth = toMsg(encodeImage(cv::Mat::zeros(2000, 3000, CV_16UC1), ImageEncoding::kPng));
  KeyframeInput kf;
  const std::string why = keyframeFromMessage(m, kf);
  EXPECT_NE(why.find("depth is 3000x2000, camera is"), std::string::npos) << why;
  EXPECT_TRUE(kf.depth.empty()) << "decoded: " << kf.depth.cols << "x" << kf.depth.rows;
  m = good();
  m.color = toMsg(encodeImage(cv::Mat::zeros(2000, 3000, CV_8UC3), ImageEncoding::kPng));
  kf = KeyframeInput{};
  EXPECT_NE(keyframeFromMessage(m, kf).find("colour is 3000x2000"), std::string::npos);
  EXPECT_TRUE(kf.color.empty() && kf.depth.empty());
}

TEST(MapperMessages, NonFinitePoseOrIntrinsics) {
  keyframe_t m = good();
  m.T_world_cam.orientation[0] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(reasonOf(m).find("non-finite pose"), std::string::npos) << reasonOf(m);
  m = good();
  m.T_world_cam.orientation[0] = m.T_world_cam.orientation[1] = 0;
  m.T_world_cam.orientation[2] = m.T_world_cam.orientation[3] = 0;  // no rotation at all
  EXPECT_NE(reasonOf(m).find("not a unit quaternion"), std::string::npos) << reasonOf(m);
  m = good();
  m.camera.cy = std::numeric_limits<double>::infinity();
  EXPECT_NE(reasonOf(m).find("camera intrinsics are not finite"), std::string::npos) << reasonOf(m);
  m = good();
  m.depth_scale = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(reasonOf(m).find("depth_scale must be positive"), std::string::npos) << reasonOf(m);
  m = good();
  m.camera.distortion[1] = -1e300;
  EXPECT_NE(reasonOf(m).find("distortion coefficient"), std::string::npos) << reasonOf(m);
  m = good();
  // Within range, but folding over inside the image: its outer rays are not numbers, and one such point
  // in the cloud crashed the map's pictures at the save.
  m.camera.distortion[0] = -0.5;
  EXPECT_NE(reasonOf(m).find("lens distortion cannot be undone at pixel"), std::string::npos) << reasonOf(m);
}

TEST(MapperMessages, PoseUpdatesAndOutgoingMessages) {
  keyframe_poses_t p;
  p.utime = 1;
  p.num_keyframes = 3;
  p.ids = {3, 9, 11};
  p.T_world_cam = {toMsg(test::translation(1, 0, 0)), toMsg(SE3::Identity()), toMsg(SE3::Identity())};
  p.T_world_cam[2].position[1] = std::numeric_limits<double>::quiet_NaN();
  std::vector<std::string> rejected;
  const std::vector<PoseUpdate> updates = poseUpdatesFromMessage(p, rejected);
  ASSERT_EQ(updates.size(), 2u);
  ASSERT_EQ(rejected.size(), 1u);
  EXPECT_EQ(rejected[0], "keyframe 11: non-finite pose");
  EXPECT_EQ(updates[1].id, 9);
  EXPECT_NEAR(updates[0].T_world_cam.translation().x(), 1.0, 1e-12);

  Mapper mapper(test::testSettings());
  ASSERT_TRUE(mapper.integrate(test::wallKeyframe(0, SE3::Identity(), 3.02)).ok);
  const occupancy_grid_t g = toGridMessage(mapper.grid(), 7);
  EXPECT_EQ(g.num_cells, g.width * g.height);
  EXPECT_EQ(g.frame_id, "world");
  EXPECT_NEAR(g.resolution, 0.05f, 1e-7);
  const octomap_t o = toOctomapMessage(mapper.occupancy(), 7);
  EXPECT_TRUE(o.binary);
  EXPECT_EQ(o.size, static_cast<int32_t>(o.data.size()));
  EXPECT_GT(o.size, 100);
  const point_cloud_t c = toCloudMessage(mapper.cloud(), 7, 1000);
  EXPECT_LE(c.num_points, 1000);
  EXPECT_GE(c.num_points, 990);
  EXPECT_EQ(c.points.size(), c.colors.size());
}

}  // namespace
}  // namespace bmp::mapper

// One keyframe into the map: back-projection (depth range, dilated mask, undistortion), the voxel filter,
// and the keyframes the mapper refuses, each with its reason.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "mapper/keyframe_cloud.hpp"
#include "mapper/mapper.hpp"
#include "mapper/voxel_filter.hpp"
#include "mapper_test_util.hpp"

namespace bmp::mapper {
namespace {

using test::wallKeyframe;

TEST(KeyframeCloud, WallBackProjectsAtItsDepth) {
  const KeyframeInput kf = wallKeyframe(0, SE3::Identity(), 2.0);
  const PointList points = backProject(kf, RayTable(kf.camera), CloudSettings{});
  ASSERT_EQ(points.size(), kf.depth.total());
  for (const auto& p : points) ASSERT_NEAR(p.z, 2.0f, 1e-4);
  EXPECT_EQ(points[0].r, 200);  // BGR in, RGB out
  EXPECT_EQ(points[0].b, 40);
  // Pixel (0, 0) lies up and to the left: x and y negative in the camera frame.
  EXPECT_NEAR(points[0].x, (0 - 79.5) / 131.25 * 2.0, 1e-4);
  EXPECT_NEAR(points[0].y, (0 - 59.5) / 131.25 * 2.0, 1e-4);
}

TEST(KeyframeCloud, DepthOutsideTheRangeIsDropped) {
  CloudSettings s;
  s.min_depth_m = 0.5;
  s.max_depth_m = 3.0;
  const KeyframeInput far = wallKeyframe(0, SE3::Identity(), 4.0, cv::Rect(0, 0, 10, 10), 2.0);
  EXPECT_EQ(backProject(far, RayTable(far.camera), s).size(), 100u);
  const KeyframeInput near = wallKeyframe(0, SE3::Identity(), 0.2, cv::Rect(0, 0, 10, 10), 1.0);
  EXPECT_EQ(backProject(near, RayTable(near.camera), s).size(), 100u);
  KeyframeInput holes = wallKeyframe(0, SE3::Identity(), 2.0);
  holes.depth(cv::Rect(0, 0, 160, 60)).setTo(0);  // no measurement
  EXPECT_EQ(backProject(holes, RayTable(holes.camera), s).size(), 160u * 60u);
}

TEST(KeyframeCloud, MaskedPixelsAndTheirMarginAreDropped) {
  KeyframeInput kf = wallKeyframe(0, SE3::Identity(), 2.0);
  kf.dynamic_mask(cv::Rect(40, 40, 20, 20)).setTo(255);
  CloudSettings s;
  s.mask_dilation_px = 0;
  EXPECT_EQ(backProject(kf, RayTable(kf.camera), s).size(), kf.depth.total() - 400);
  s.mask_dilation_px = 3;
  const std::size_t dilated = backProject(kf, RayTable(kf.camera), s).size();
  EXPECT_LT(dilated, kf.depth.total() - 26 * 26 + 40);  // about a 26x26 square with rounded corners
  EXPECT_GT(dilated, kf.depth.total() - 26 * 26);
  s.pixel_step = 2;
  EXPECT_LT(backProject(kf, RayTable(kf.camera), s).size(), dilated / 3);
}

TEST(KeyframeCloud, DistortedPixelsAreUndistorted) {
  KeyframeInput kf = wallKeyframe(0, SE3::Identity(), 2.0);
  kf.camera.distortion = {0.1, -0.05, 0.001, -0.001, 0.0};
  const PointList points = backProject(kf, RayTable(kf.camera), CloudSettings{});
  const CameraModel model(kf.camera);
  for (const std::size_t i : {std::size_t{0}, std::size_t{161}, points.size() - 1}) {
    const Eigen::Vector2d uv = model.project(points[i].position().cast<double>());
    const auto u = static_cast<int>(i % 160), v = static_cast<int>(i / 160);  // the pixel it came from
    EXPECT_NEAR(uv.x(), u, 0.05) << i;
    EXPECT_NEAR(uv.y(), v, 0.05) << i;
  }
}

TEST(VoxelFilter, OnePointPerVoxelWithAveragedColour) {
  PointList in;
  in.push_back({0.01f, 0.01f, 0.01f, 100, 0, 0});
  in.push_back({0.03f, 0.03f, 0.03f, 200, 0, 0});
  in.push_back({0.51f, 0.01f, 0.01f, 0, 50, 0});
  const PointList out = voxelFilter(in, 0.05);
  ASSERT_EQ(out.size(), 2u);
  const auto& first = out[0].x < 0.1f ? out[0] : out[1];
  EXPECT_NEAR(first.x, 0.02f, 1e-6);
  EXPECT_EQ(first.r, 150);
}

TEST(VoxelFilter, HugeExtentsAreFilteredInSlabs) {
  // 10 km apart at 1 cm: far beyond PCL's 32-bit voxel index, which would pass the cloud through unfiltered.
  PointList in;
  for (int i = 0; i < 10; ++i) {
    in.push_back({0.001f * i, 0.0f, 0.0f, 1, 1, 1});
    in.push_back({10000.0f + 0.001f * i, 5000.0f, 0.0f, 1, 1, 1});
  }
  EXPECT_EQ(voxelFilter(in, 0.01).size(), 2u);
}

class RefusedKeyframe : public ::testing::Test {
 protected:
  void expectRefused(const KeyframeInput& kf, const std::string& words) {
    const IntegrateResult r = mapper.integrate(kf);
    EXPECT_FALSE(r.ok);
    EXPECT_NE(r.reason.find(words), std::string::npos) << r.reason;
    EXPECT_EQ(mapper.keyframeCount(), 1u);  // only the good one below
  }
  void SetUp() override { ASSERT_TRUE(mapper.integrate(wallKeyframe(0, SE3::Identity(), 2.0)).ok); }
  Mapper mapper{test::testSettings()};
};

TEST_F(RefusedKeyframe, MaskOfTheWrongSize) {
  KeyframeInput kf = wallKeyframe(1, SE3::Identity(), 2.0);
  kf.dynamic_mask = cv::Mat::zeros(60, 80, CV_8UC1);
  expectRefused(kf, "mask is 80x60");
}

TEST_F(RefusedKeyframe, DepthOfTheWrongSizeOrType) {
  KeyframeInput kf = wallKeyframe(1, SE3::Identity(), 2.0);
  kf.depth = cv::Mat::zeros(100, 160, CV_16UC1);
  expectRefused(kf, "depth is 160x100");
  kf.depth = cv::Mat::zeros(120, 160, CV_32FC1);
  expectRefused(kf, "depth has the wrong pixel type");
}

TEST_F(RefusedKeyframe, NonFinitePoseOrIntrinsics) {
  KeyframeInput kf = wallKeyframe(1, SE3::Identity(), 2.0);
  kf.T_world_cam.translation().x() = std::numeric_limits<double>::quiet_NaN();
  expectRefused(kf, "non-finite pose");
  kf = wallKeyframe(1, SE3::Identity(), 2.0);
  kf.camera.fx = std::numeric_limits<double>::infinity();
  expectRefused(kf, "camera intrinsics are not finite");
  kf = wallKeyframe(1, SE3::Identity(), 2.0);
  kf.camera.depth_scale = 0;
  expectRefused(kf, "depth_scale");
}

// A focal length no camera has put points 1e22 m away (fx = 1e-20), and a huge camera cost 4.9 GB and 41 s
// before it could be refused as not the map's.
TEST_F(RefusedKeyframe, ImplausibleCamera) {
  KeyframeInput kf = wallKeyframe(1, SE3::Identity(), 2.0);
  kf.camera.fx = kf.camera.fy = 1e-20;
  expectRefused(kf, "is not a camera's for a 160x120 image");
  kf = wallKeyframe(1, SE3::Identity(), 2.0);
  kf.camera.cx = -5;
  expectRefused(kf, "principal point lies outside the image");
  kf = wallKeyframe(1, SE3::Identity(), 2.0);
  kf.camera.width = kf.camera.height = 8192;
  expectRefused(kf, "8192x8192 is not a camera's (at most 16777216 pixels)");
}

TEST_F(RefusedKeyframe, RepeatedId) {
  expectRefused(wallKeyframe(0, SE3::Identity(), 3.0), "already mapped");
}

}  // namespace
}  // namespace bmp::mapper

// The synthetic scene: determinism, exact depth, pose/texture consistency, masks, and ORB coverage.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <ctime>
#include <memory>

#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>

#include "bmp/common/camera_model.hpp"
#include "bmp/common/timing.hpp"
#include "capture/synthetic_scene.hpp"

namespace bmp::capture {
namespace {

// Scenes are costly to build (textures): the suite shares one dynamic and one static scene, each built
// on first use (ctest runs every test in its own process).
class SyntheticSceneTest : public ::testing::Test {
 protected:
  static void TearDownTestSuite() {
    dynamic_.reset();
    static_.reset();
  }
  static const SyntheticScene& dynamicScene() {
    if (!dynamic_) dynamic_ = std::make_unique<SyntheticScene>(SyntheticSceneConfig{});
    return *dynamic_;
  }
  static const SyntheticScene& staticScene() {
    if (!static_) {
      SyntheticSceneConfig still;
      still.num_moving_objects = 0;
      static_ = std::make_unique<SyntheticScene>(still);
    }
    return *static_;
  }

 private:
  static std::unique_ptr<SyntheticScene> dynamic_;
  static std::unique_ptr<SyntheticScene> static_;
};
std::unique_ptr<SyntheticScene> SyntheticSceneTest::dynamic_;
std::unique_ptr<SyntheticScene> SyntheticSceneTest::static_;

bool identical(const cv::Mat& a, const cv::Mat& b) {
  return a.size() == b.size() && a.type() == b.type() && cv::norm(a, b, cv::NORM_INF) == 0;
}

// Distance from p to the surface of box b when p is (nearly) inside it; a large number otherwise.
double distanceToBoxSurface(const Eigen::Vector3d& p, const AlignedBox& b, double tol) {
  if (((p - b.lo).array() < -tol).any() || ((b.hi - p).array() < -tol).any()) return 1e9;
  double d = 1e9;
  for (int a = 0; a < 3; ++a) d = std::min({d, std::abs(p[a] - b.lo[a]), std::abs(p[a] - b.hi[a])});
  return d;
}

TEST_F(SyntheticSceneTest, RendersTheConfiguredFormats) {
  const SyntheticFrame f = dynamicScene().render(0);
  EXPECT_EQ(f.bgr.type(), CV_8UC3);
  EXPECT_EQ(f.depth.type(), CV_16UC1);
  EXPECT_EQ(f.mask.type(), CV_8UC1);
  EXPECT_EQ(f.bgr.size(), cv::Size(640, 480));
  EXPECT_DOUBLE_EQ(f.stamp, 1000.0);
  EXPECT_DOUBLE_EQ(dynamicScene().render(30).stamp, 1001.0);
  EXPECT_EQ(dynamicScene().numFrames(), 300);
  EXPECT_THROW(dynamicScene().render(300), std::out_of_range);
  EXPECT_THROW(dynamicScene().render(-1), std::out_of_range);
}

TEST_F(SyntheticSceneTest, IsDeterministicAndFollowsTheSeed) {
  const SyntheticFrame a = dynamicScene().render(42);
  const SyntheticFrame b = dynamicScene().render(42);
  EXPECT_TRUE(identical(a.bgr, b.bgr) && identical(a.depth, b.depth) && identical(a.mask, b.mask));
  SyntheticSceneConfig other;
  other.seed = 7;
  const SyntheticScene reseeded(other);
  const SyntheticScene rebuilt(SyntheticSceneConfig{});
  EXPECT_TRUE(identical(rebuilt.render(42).bgr, a.bgr));
  EXPECT_FALSE(identical(reseeded.render(42).bgr, a.bgr));
  // Noise changes from frame to frame, not only with the seed.
  EXPECT_FALSE(identical(dynamicScene().render(43).bgr, a.bgr));
}

TEST_F(SyntheticSceneTest, DepthBackProjectsOntoSceneSurfaces) {
  const CameraModel model(dynamicScene().camera());
  for (int index : {0, 97, 211}) {
    const SyntheticFrame f = dynamicScene().render(index);
    const auto objects = dynamicScene().movingObjects(index);
    int checked = 0, masked = 0;
    for (int v = 1; v < f.depth.rows; v += 7) {
      for (int u = 3; u < f.depth.cols; u += 7) {
        const uint16_t raw = f.depth.at<uint16_t>(v, u);
        if (raw == 0) continue;
        const Eigen::Vector3d p =
            f.T_world_cam * model.backProject({u, v}, raw / dynamicScene().camera().depth_scale);
        const double tol = 1e-3;  // depth quantisation is 0.2 mm
        double on_static = distanceToBoxSurface(p, dynamicScene().room(), tol);
        for (const auto& box : dynamicScene().staticBoxes())
          on_static = std::min(on_static, distanceToBoxSurface(p, box, tol));
        double on_object = 1e9;
        for (const auto& o : objects)
          on_object = std::min(on_object, distanceToBoxSurface(o.T_world_object.inverse() * p, o.box, tol));
        if (f.mask.at<uint8_t>(v, u)) {
          ++masked;
          ASSERT_LT(on_object, tol) << "frame " << index << " pixel " << u << "," << v;
        } else {
          ASSERT_LT(on_static, tol) << "frame " << index << " pixel " << u << "," << v;
        }
        ++checked;
      }
    }
    EXPECT_GT(checked, 5000);
    std::printf("frame %d: %d pixels on surfaces, %d on moving objects\n", index, checked, masked);
  }
}

// Warps frame j into frame i through depth and ground-truth poses; returns the mean absolute grey
// difference over static, mutually visible pixels.
double warpError(const SyntheticFrame& fi, const SyntheticFrame& fj, const SE3& T_world_cam_i,
                 const CameraIntrinsics& k) {
  const CameraModel model(k);
  cv::Mat gi, gj;
  cv::cvtColor(fi.bgr, gi, cv::COLOR_BGR2GRAY);
  cv::cvtColor(fj.bgr, gj, cv::COLOR_BGR2GRAY);
  const SE3 T_i_j = T_world_cam_i.inverse() * fj.T_world_cam;
  double sum = 0;
  int n = 0;
  for (int v = 0; v < k.height; v += 3) {
    for (int u = 0; u < k.width; u += 3) {
      const uint16_t raw = fj.depth.at<uint16_t>(v, u);
      if (raw == 0 || fj.mask.at<uint8_t>(v, u)) continue;
      const Eigen::Vector3d p = T_i_j * model.backProject({u, v}, raw / k.depth_scale);
      if (p.z() < 0.1) continue;
      const Eigen::Vector2d uv = model.projectPinhole(p);
      const int ui = static_cast<int>(std::lround(uv.x())), vi = static_cast<int>(std::lround(uv.y()));
      if (!model.inImage(uv, 2.0) || fi.mask.at<uint8_t>(vi, ui)) continue;
      if (std::abs(fi.depth.at<uint16_t>(vi, ui) / k.depth_scale - p.z()) > 0.02) continue;  // occluded
      cv::Mat sample;
      cv::getRectSubPix(gi, cv::Size(1, 1), cv::Point2f(uv.x(), uv.y()), sample, CV_32F);
      sum += std::abs(sample.at<float>(0, 0) - gj.at<uint8_t>(v, u));
      ++n;
    }
  }
  EXPECT_GT(n, 5000);
  return sum / std::max(n, 1);
}

TEST_F(SyntheticSceneTest, PosesDepthAndTexturesAgreeAcrossFrames) {
  const CameraIntrinsics& k = dynamicScene().camera();
  for (auto [i, j] : {std::pair{10, 16}, std::pair{120, 129}}) {
    const SyntheticFrame fi = dynamicScene().render(i), fj = dynamicScene().render(j);
    const double error = warpError(fi, fj, fi.T_world_cam, k);
    // A pose wrong by 1 cm must look clearly worse: the poses are what the texture says.
    SE3 shifted = fi.T_world_cam;
    shifted.translation() += shifted.linear() * Eigen::Vector3d(0.01, 0, 0);
    const double shifted_error = warpError(fi, fj, shifted, k);
    std::printf("frames %d->%d: warp error %.2f grey levels, %.2f with a 1 cm pose error\n", j, i, error,
                shifted_error);
    EXPECT_LT(error, 6.0);
    EXPECT_GT(shifted_error, 2.0 * error);
  }
}

TEST_F(SyntheticSceneTest, MasksMarkMovingObjectsAtDepthEdges) {
  int frames_with_objects = 0;
  for (int index = 0; index < dynamicScene().numFrames(); index += 20) {
    const SyntheticFrame f = dynamicScene().render(index);
    EXPECT_EQ(cv::countNonZero(staticScene().render(index).mask), 0) << "static frame " << index;
    if (cv::countNonZero(f.mask) < 500) continue;
    ++frames_with_objects;
    // Along rows, a mask edge is a silhouette edge: the depth jumps there, except where feet meet the floor.
    int edges = 0, jumps = 0;
    for (int v = 0; v < f.mask.rows; ++v) {
      for (int u = 0; u + 1 < f.mask.cols; ++u) {
        if (f.mask.at<uint8_t>(v, u) == f.mask.at<uint8_t>(v, u + 1)) continue;
        ++edges;
        const int d0 = f.depth.at<uint16_t>(v, u), d1 = f.depth.at<uint16_t>(v, u + 1);
        if (std::abs(d0 - d1) > 0.05 * dynamicScene().camera().depth_scale) ++jumps;
      }
    }
    EXPECT_GT(jumps, 0.8 * edges) << "frame " << index;
  }
  EXPECT_GE(frames_with_objects, 5);
}

TEST_F(SyntheticSceneTest, OrbFindsDenseWellSpreadCorners) {
  const auto orb = cv::ORB::create(1000);
  for (const SyntheticScene* scene : {&dynamicScene(), &staticScene()}) {
    for (int index : {0, 75, 150, 225, 299}) {
      const SyntheticFrame f = scene->render(index);
      cv::Mat grey;
      cv::cvtColor(f.bgr, grey, cv::COLOR_BGR2GRAY);
      std::vector<cv::KeyPoint> keypoints;
      orb->detect(grey, keypoints);
      int cells[16] = {0};
      for (const auto& kp : keypoints)
        ++cells[std::min(3, static_cast<int>(kp.pt.y * 4 / grey.rows)) * 4 +
                std::min(3, static_cast<int>(kp.pt.x * 4 / grey.cols))];
      int covered = 0;
      for (int c : cells) covered += c >= 10 ? 1 : 0;
      std::printf("frame %d: %zu ORB keypoints, %d of 16 cells with >= 10\n", index, keypoints.size(),
                  covered);
      EXPECT_GE(keypoints.size(), 500u) << "frame " << index;
      EXPECT_GE(covered, 12) << "frame " << index;
    }
  }
}

TEST_F(SyntheticSceneTest, CameraAndWalkersMoveAtPlausibleSpeeds) {
  const Trajectory gt = dynamicScene().groundTruth();
  ASSERT_EQ(gt.size(), 300u);
  double path = 0, max_step = 0, max_turn = 0;
  for (std::size_t i = 1; i < gt.size(); ++i) {
    const SE3 delta = gt[i - 1].T_world_cam.inverse() * gt[i].T_world_cam;
    path += delta.translation().norm();
    max_step = std::max(max_step, delta.translation().norm());
    max_turn = std::max(max_turn, rotationAngle(delta));
    EXPECT_NEAR(gt[i].stamp - gt[i - 1].stamp, 1.0 / 30, 2e-6);
  }
  const double speed = path / (gt.back().stamp - gt.front().stamp);
  EXPECT_GT(speed, 0.2);
  EXPECT_LT(speed, 0.6);
  EXPECT_LT(max_step, 0.025);
  EXPECT_LT(max_turn, 1.5 * CV_PI / 180);
  const auto a = dynamicScene().movingObjects(100), b = dynamicScene().movingObjects(101);
  ASSERT_EQ(a.size(), 2u);
  for (std::size_t k = 0; k < a.size(); ++k) {
    const double walker_speed = (b[k].position - a[k].position).norm() * 30;
    EXPECT_GT(walker_speed, 0.5);
    EXPECT_LT(walker_speed, 1.6);
  }
}

}  // namespace
}  // namespace bmp::capture

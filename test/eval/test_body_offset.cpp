// The ground truth's orientations against the estimate's camera frame: a constant offset (a motion-capture
// marker's frame) is found and measured; a camera-frame ground truth, or noisy orientations, are not flagged.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "eval/ate.hpp"
#include "eval/body_offset.hpp"
#include "eval_test_util.hpp"

namespace bmp::eval {

using test::pose;

namespace {

Trajectory curve(int n) {
  Trajectory t;
  for (int k = 0; k < n; ++k) {
    const double s = 0.1 * k;
    t.push_back(
        {100.0 + 0.1 * k, pose(2 * std::cos(s), 1.5 * std::sin(1.3 * s), 0.4 * s, 0.2 * s, 0.05 * s)});
  }
  return t;
}

// Each pose moved in its own body frame by B: what a tracker of a camera mounted at B from the marker sees.
Trajectory withBody(const Trajectory& t, const SE3& B) {
  Trajectory out = t;
  for (auto& p : out) p.T_world_cam = p.T_world_cam * B;
  return out;
}

const SE3 kOtherWorld = pose(3.0, -1.0, 0.5, 1.1, -0.4, 0.3);

}  // namespace

TEST(evalBodyOffset, ConstantMarkerOffsetIsFoundWithItsAngle) {
  const Trajectory gt = curve(80);
  // The estimate is the camera: the marker (ground truth) sits 172 degrees from it, as on Bonn.
  const SE3 B =
      makeSE3({0.01, -0.01, 0.01}, Eigen::Quaterniond(Eigen::AngleAxisd(
                                       172.0 * M_PI / 180.0, Eigen::Vector3d(0.2, 1.0, 0.1).normalized())));
  const Trajectory est = test::transformed(withBody(gt, B.inverse()), kOtherWorld);
  const BodyOffset offset = measureBodyOffset(gt, est, computeAte(gt, est), 0.0);
  EXPECT_EQ(offset.pairs, 80u);
  // The 1.7 cm lever arm makes the positions not quite rigidly related, so the alignment (and with it the
  // measured offset) is a little off: a tenth of a degree here.
  EXPECT_NEAR(offset.angle_deg, 172.0, 0.2);
  EXPECT_LT(offset.spread_deg, 0.3);
  EXPECT_TRUE(offset.constant());
}

TEST(evalBodyOffset, CameraFrameGroundTruthIsNotFlagged) {
  const Trajectory gt = curve(80);
  const Trajectory est = test::transformed(gt, kOtherWorld);
  const BodyOffset offset = measureBodyOffset(gt, est, computeAte(gt, est), 0.0);
  EXPECT_LT(offset.angle_deg, 0.01);
  EXPECT_FALSE(offset.constant());
}

// Orientation noise of a few degrees (a poor tracker) has a spread, not a constant offset.
TEST(evalBodyOffset, NoisyOrientationsAreNotAConstantOffset) {
  const Trajectory gt = curve(200);
  Trajectory est = gt;
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 8.0 * M_PI / 180.0);
  for (auto& p : est)
    p.T_world_cam.linear() =
        p.T_world_cam.linear() * (Eigen::AngleAxisd(noise(rng), Eigen::Vector3d::UnitX()) *
                                  Eigen::AngleAxisd(noise(rng), Eigen::Vector3d::UnitY()))
                                     .toRotationMatrix();
  const BodyOffset offset = measureBodyOffset(gt, est, computeAte(gt, est), 0.0);
  EXPECT_GT(offset.spread_deg, 3.0);
  EXPECT_FALSE(offset.constant());
}

}  // namespace bmp::eval

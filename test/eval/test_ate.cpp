#include <cmath>

#include <gtest/gtest.h>

#include "eval/ate.hpp"
#include "eval/eval_error.hpp"
#include "eval_test_util.hpp"

namespace bmp::eval {

using test::pose;

namespace {
// A curve that is not planar, so the alignment is unique.
Trajectory curve(int n, double dt = 0.1) {
  Trajectory t;
  for (int k = 0; k < n; ++k) {
    const double s = 0.1 * k;
    t.push_back({100.0 + dt * k, pose(2 * std::cos(s), 1.5 * std::sin(1.3 * s), 0.4 * s, 0.2 * s, 0.05 * s)});
  }
  return t;
}
const SE3 kOtherWorld = pose(3.0, -1.0, 0.5, 1.1, -0.4, 0.3);
}  // namespace

TEST(evalAte, RigidlyMovedGroundTruthHasZeroError) {
  const Trajectory gt = curve(60);
  const Trajectory est = test::transformed(gt, kOtherWorld);
  const AteResult r = computeAte(gt, est);
  EXPECT_EQ(r.stats.count, 60u);
  EXPECT_LT(r.stats.rmse, 1e-9);
  EXPECT_LT(r.stats.max, 1e-9);
  // The alignment is the inverse of the applied transform.
  const SE3 expected = kOtherWorld.inverse();
  EXPECT_LT((r.alignment.rotation - expected.linear()).norm(), 1e-9);
  EXPECT_LT((r.alignment.translation - expected.translation()).norm(), 1e-9);
}

// Poses come in pairs at the same place; the estimate of a pair is +e and -e along z. Such noise has zero
// mean and no cross-covariance with the positions, so no rigid motion can absorb it and the errors stay
// exactly e: pairs alternate e = 3 cm and e = 1 cm, hence rmse sqrt((9+1)/2) cm, mean 2 cm, std 1 cm.
TEST(evalAte, KnownNoiseGivesKnownStatistics) {
  const double e_big = 0.03;
  const double e_small = 0.01;
  Trajectory gt;
  Trajectory est_local;
  for (int m = 0; m < 20; ++m) {
    const double s = 0.3 * m;
    const SE3 place = pose(2 * std::cos(s), 1.5 * std::sin(1.3 * s), 0.4 * s + 0.1 * std::sin(3 * s));
    const double e = (m % 2 == 0) ? e_big : e_small;
    for (int side = 0; side < 2; ++side) {
      const double stamp = 10.0 + 0.1 * (2 * m + side);
      gt.push_back({stamp, place});
      SE3 noisy = place;
      noisy.translation().z() += side == 0 ? e : -e;
      est_local.push_back({stamp + 0.004, noisy});  // stamps jittered within max_difference
    }
  }
  const AteResult r = computeAte(gt, test::transformed(est_local, kOtherWorld));
  ASSERT_EQ(r.stats.count, 40u);
  EXPECT_NEAR(r.stats.rmse, std::sqrt((e_big * e_big + e_small * e_small) / 2), 1e-12);
  EXPECT_NEAR(r.stats.mean, 0.02, 1e-12);
  EXPECT_NEAR(r.stats.median, 0.02, 1e-12);
  EXPECT_NEAR(r.stats.std, 0.01, 1e-12);
  EXPECT_NEAR(r.stats.min, e_small, 1e-12);
  EXPECT_NEAR(r.stats.max, e_big, 1e-12);
}

TEST(evalAte, ScaleMultipliesEstimatedPositions) {
  const Trajectory gt = curve(40);
  Trajectory half = gt;
  for (auto& p : half) p.T_world_cam.translation() *= 0.5;
  AteOptions options;
  EXPECT_GT(computeAte(gt, half, options).stats.rmse, 0.1);
  options.scale = 2.0;
  EXPECT_LT(computeAte(gt, half, options).stats.rmse, 1e-9);
}

TEST(evalAte, OnlyAssociatedPairsCountAndOffsetShiftsStamps) {
  const Trajectory gt = curve(50);
  Trajectory est;
  for (std::size_t k = 0; k < gt.size(); k += 2) est.push_back({gt[k].stamp - 7.0, gt[k].T_world_cam});
  EXPECT_THROW(computeAte(gt, est), EvalError);
  AteOptions options;
  options.offset = 7.0;
  const AteResult r = computeAte(gt, est, options);
  EXPECT_EQ(r.stats.count, 25u);
  EXPECT_LT(r.stats.rmse, 1e-9);
  EXPECT_DOUBLE_EQ(r.pairs.front().gt_stamp, gt.front().stamp);
  EXPECT_DOUBLE_EQ(r.pairs.front().est_stamp, est.front().stamp);
}

TEST(evalAte, AlignedTrajectoryLandsOnGroundTruth) {
  const Trajectory gt = curve(30);
  const Trajectory est = test::transformed(gt, kOtherWorld);
  const AteResult r = computeAte(gt, est);
  const Trajectory aligned = alignedTrajectory(est, r.alignment, 1.0);
  ASSERT_EQ(aligned.size(), gt.size());
  for (std::size_t k = 0; k < gt.size(); ++k) {
    EXPECT_LT((aligned[k].T_world_cam.matrix() - gt[k].T_world_cam.matrix()).norm(), 1e-9);
  }
}

TEST(evalAte, FewerThanTwoPairsIsAnError) {
  const Trajectory gt = curve(10);
  const Trajectory one = {gt[3]};
  try {
    computeAte(gt, one);
    FAIL() << "expected EvalError";
  } catch (const EvalError& e) {
    EXPECT_NE(std::string(e.what()).find("only one estimated stamp"), std::string::npos) << e.what();
  }
  EXPECT_EQ(computeAte(gt, {gt[3], gt[4]}).stats.count, 2u);
}

TEST(evalAte, NoOverlapNamesTheSpans) {
  const Trajectory gt = curve(10);
  Trajectory est = gt;
  for (auto& p : est) p.stamp += 50.0;
  try {
    computeAte(gt, est);
    FAIL() << "expected EvalError";
  } catch (const EvalError& e) {
    EXPECT_NE(std::string(e.what()).find("no estimated stamp"), std::string::npos) << e.what();
  }
}

}  // namespace bmp::eval

#include <cmath>

#include <gtest/gtest.h>

#include "eval/eval_error.hpp"
#include "eval/rpe.hpp"
#include "eval_test_util.hpp"

namespace bmp::eval {

using test::pose;

namespace {
constexpr double kDeg = 180.0 / M_PI;

// Positions along x; the step from frame k to k+1 is step(k). Stamps start at t0, spacing dt.
template <typename Step>
Trajectory alongX(int n, double t0, double dt, Step step) {
  Trajectory t;
  double x = 0;
  for (int k = 0; k < n; ++k) {
    t.push_back({t0 + dt * k, pose(x, 0, 0)});
    x += step(k);
  }
  return t;
}
RpeOptions frames(double delta) {
  RpeOptions o;
  o.delta = delta;
  o.unit = DeltaUnit::kFrames;
  return o;
}
}  // namespace

TEST(evalRpe, FindClosestIndexIsTheScriptsBinarySearch) {
  const std::vector<double> L = {0, 1, 2, 3};
  EXPECT_EQ(findClosestIndex(L, 1.0), 1u);
  EXPECT_EQ(findClosestIndex(L, 1.4), 1u);
  EXPECT_EQ(findClosestIndex(L, 1.5), 2u);  // a tie goes to the element the search visits first
  EXPECT_EQ(findClosestIndex(L, -5), 0u);
  EXPECT_EQ(findClosestIndex(L, 10), 3u);
  EXPECT_EQ(findClosestIndex({7.0}, 0.0), 0u);
}

TEST(evalRpe, RigidlyMovedGroundTruthHasZeroError) {
  Trajectory gt;
  for (int k = 0; k < 80; ++k) {
    const double s = 0.05 * k;
    gt.push_back({5.0 + 0.05 * k, pose(std::cos(s), std::sin(2 * s), 0.3 * s, 0.4 * s, 0.1 * s, -0.2 * s)});
  }
  const Trajectory est = test::transformed(gt, pose(1, 2, 3, 0.7, 0.2, -0.5));
  const RpeResult r = computeRpe(gt, est);
  EXPECT_EQ(r.trans.count, 80u - 21u);  // delta 1 s = 20 frames; pairs ending on the last frame are dropped
  EXPECT_LT(r.trans.max, 1e-9);
  // acos near 1 turns rounding of 1e-16 into angles of about 1e-8 rad.
  EXPECT_LT(r.rot_deg.max, 1e-5);
}

// Frame steps of the estimate alternate 1.0 and 1.1 m against 1.0 m of the ground truth: one-frame pairs
// alternate errors 0 and 0.1 m, two-frame pairs all have 0.1 m. With n frames there are n-2 one-frame pairs
// and n-3 two-frame pairs, because pairs whose second frame is the last one are dropped (as the script
// does).
TEST(evalRpe, FrameDeltaByHand) {
  const Trajectory gt = alongX(10, 0.0, 0.1, [](int) { return 1.0; });
  const Trajectory est = alongX(10, 0.0, 0.1, [](int k) { return k % 2 == 0 ? 1.0 : 1.1; });
  const RpeResult one = computeRpe(gt, est, frames(1));
  ASSERT_EQ(one.trans.count, 8u);
  EXPECT_NEAR(one.trans.mean, 0.05, 1e-12);
  EXPECT_NEAR(one.trans.median, 0.05, 1e-12);
  EXPECT_NEAR(one.trans.rmse, std::sqrt(0.005), 1e-12);
  EXPECT_NEAR(one.trans.std, 0.05, 1e-12);
  EXPECT_NEAR(one.trans.min, 0.0, 1e-12);
  EXPECT_NEAR(one.trans.max, 0.1, 1e-12);
  EXPECT_LT(one.rot_deg.max, 1e-5);
  EXPECT_EQ(one.pairs.front().i, 0u);
  EXPECT_EQ(one.pairs.front().j, 1u);

  const RpeResult two = computeRpe(gt, est, frames(2));
  ASSERT_EQ(two.trans.count, 7u);
  EXPECT_NEAR(two.trans.min, 0.1, 1e-12);
  EXPECT_NEAR(two.trans.max, 0.1, 1e-12);
}

// Turning in place 0.12 rad per frame against 0.10: every one-frame pair is off by 0.02 rad.
TEST(evalRpe, RotationErrorInDegrees) {
  Trajectory gt;
  Trajectory est;
  for (int k = 0; k < 12; ++k) {
    gt.push_back({0.1 * k, pose(0, 0, 0, 0.10 * k)});
    est.push_back({0.1 * k, pose(0, 0, 0, 0.12 * k)});
  }
  const RpeResult r = computeRpe(gt, est, frames(1));
  ASSERT_EQ(r.rot_deg.count, 10u);
  EXPECT_NEAR(r.rot_deg.min, 0.02 * kDeg, 1e-9);
  EXPECT_NEAR(r.rot_deg.max, 0.02 * kDeg, 1e-9);
  EXPECT_LT(r.trans.max, 1e-12);
}

// 10 Hz, delta 0.5 s = 5 frames; estimated stamps 10 ms late still find their ground truth.
TEST(evalRpe, SecondsDeltaByHand) {
  const Trajectory gt = alongX(30, 50.0, 0.1, [](int) { return 1.0; });
  const Trajectory est = alongX(30, 50.01, 0.1, [](int) { return 1.1; });
  const RpeResult r = computeRpe(gt, est);  // default: 1 s
  ASSERT_EQ(r.trans.count, 30u - 11u);
  EXPECT_NEAR(r.trans.mean, 1.0, 1e-9);
  RpeOptions half;
  half.delta = 0.5;
  const RpeResult h = computeRpe(gt, est, half);
  ASSERT_EQ(h.trans.count, 30u - 6u);
  EXPECT_NEAR(h.trans.min, 0.5, 1e-9);
  EXPECT_NEAR(h.trans.max, 0.5, 1e-9);
  EXPECT_NEAR(h.gt_interval, 0.1, 1e-9);
  EXPECT_EQ(h.pairs.front().j, 5u);
}

// Pairs more than two ground-truth intervals (0.2 s) away from any ground-truth stamp are skipped. Estimated
// stamps are 20 ms late; ground truth ends at 1.9 s. Pair i = 19 (1.92 s -> 2.02 s) still passes, but both
// ends find the last ground-truth pose, so it has no true motion and an error of the full 1 m step.
TEST(evalRpe, PairsOutsideGroundTruthAreSkipped) {
  const Trajectory gt = alongX(20, 0.0, 0.1, [](int) { return 1.0; });    // 0 .. 1.9 s
  const Trajectory est = alongX(40, 0.02, 0.1, [](int) { return 1.0; });  // 0.02 .. 3.92 s
  const RpeResult r = computeRpe(gt, est, frames(1));
  ASSERT_EQ(r.trans.count, 20u);
  EXPECT_EQ(r.pairs.back().i, 19u);
  EXPECT_NEAR(r.pairs.back().trans_error, 1.0, 1e-12);
  EXPECT_NEAR(r.pairs[18].trans_error, 0.0, 1e-12);
}

TEST(evalRpe, ScaleAppliesToEstimatedTranslation) {
  const Trajectory gt = alongX(10, 0.0, 0.1, [](int) { return 1.0; });
  const Trajectory est = alongX(10, 0.0, 0.1, [](int) { return 0.5; });
  RpeOptions o = frames(1);
  EXPECT_NEAR(computeRpe(gt, est, o).trans.max, 0.5, 1e-12);
  o.scale = 2.0;
  EXPECT_LT(computeRpe(gt, est, o).trans.max, 1e-12);
}

// Pins evaluate_rpe.py's composition: error = inv(scale(inv(E_j) E_i)) * inv(G_j) G_i = A * inv(B) with
// A, B the estimated and true motions. Both move 1 m along x, but the estimate also turns 90 degrees:
// A * inv(B) has translation (1,0,0) - Rz(90)(1,0,0) = (1,-1,0), so the script reports sqrt(2) m (the
// other composition, inv(A) * B, would give 0).
TEST(evalRpe, CompositionFollowsTheScript) {
  const Trajectory gt = {{0.0, pose(0, 0, 0)}, {0.1, pose(1, 0, 0)}, {0.2, pose(2, 0, 0)}};
  const Trajectory est = {{0.0, pose(0, 0, 0)}, {0.1, pose(1, 0, 0, M_PI / 2)}, {0.2, pose(2, 0, 0)}};
  const RpeResult r = computeRpe(gt, est, frames(1));
  ASSERT_EQ(r.trans.count, 1u);
  EXPECT_NEAR(r.trans.max, std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(r.rot_deg.max, 90.0, 1e-9);
}

TEST(evalRpe, TooShortGivesNoPairs) {
  const Trajectory one = {{0.0, pose(0, 0, 0)}};
  EXPECT_EQ(computeRpe(one, one).trans.count, 0u);
  EXPECT_THROW(parseDeltaUnit("m"), EvalError);
  EXPECT_EQ(parseDeltaUnit("f"), DeltaUnit::kFrames);
}

}  // namespace bmp::eval

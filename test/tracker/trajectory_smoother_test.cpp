// The written trajectory's smoother (trajectory_smoother.hpp): weighted by each frame's position std, against
// the camera's acceleration, and never across a loss, a gap or a step back in time.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "tracker/trajectory_smoother.hpp"

namespace bmp::tracker {
namespace {

constexpr double kFps = 30.0;

// A camera path as the synthetic scenes move it: sinusoids of 0.3-0.7 m over 5-11 s (under 0.4 m/s^2).
Eigen::Vector3d pathAt(double t) {
  const double w = 2.0 * M_PI;
  return {0.7 * std::sin(w * t / 11.0), 0.3 * std::sin(w * t / 7.0), 0.15 * std::cos(w * t / 5.0)};
}

std::vector<SmootherSample> noisyPath(int n, double std_m, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, std_m > 0.0 ? std_m : 1.0);
  std::vector<SmootherSample> s;
  for (int i = 0; i < n; ++i) {
    const double t = i / kFps;
    const Eigen::Vector3d n(noise(rng), noise(rng), noise(rng));
    s.push_back({t, pathAt(t) + (std_m > 0.0 ? n : Eigen::Vector3d::Zero()), std_m, false});
  }
  return s;
}

double rmsError(const std::vector<Eigen::Vector3d>& p, const std::vector<SmootherSample>& s) {
  double sum = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) sum += (p[i] - pathAt(s[i].stamp)).squaredNorm();
  return std::sqrt(sum / static_cast<double>(p.size()));
}

std::vector<Eigen::Vector3d> positionsOf(const std::vector<SmootherSample>& s) {
  std::vector<Eigen::Vector3d> p;
  for (const auto& x : s) p.push_back(x.position);
  return p;
}

TEST(TrajectorySmoother, ANoisyPathComesCloserToTheTruth) {
  const std::vector<SmootherSample> s = noisyPath(300, 0.01, 1);
  const double before = rmsError(positionsOf(s), s);
  const double after = rmsError(smoothPositions(s, {}), s);
  EXPECT_NEAR(before, 0.01 * std::sqrt(3.0), 0.002);
  // The measured factor is about 0.3; without the acceleration terms the solve would leave it at 1.
  EXPECT_LT(after, 0.5 * before) << before << " -> " << after;
}

// A shaken hand-held camera: 0.1-0.3 m at periods of 1-1.5 s, about 3.5 m/s^2 per axis (RMS), far over the
// default floor of 1 m/s^2.
Eigen::Vector3d shakenPathAt(double t) {
  const double w = 2.0 * M_PI;
  return {0.3 * std::sin(w * t / 1.5), 0.2 * std::sin(w * t / 1.2), 0.1 * std::cos(w * t / 1.0)};
}

double shakenAccelSigma() {
  const double w = 2.0 * M_PI;
  auto peak = [&](double amplitude, double period) { return amplitude * std::pow(w / period, 2); };
  const double sum = std::pow(peak(0.3, 1.5), 2) + std::pow(peak(0.2, 1.2), 2) + std::pow(peak(0.1, 1.0), 2);
  return std::sqrt(sum / 2.0 / 3.0);  // RMS of each sinusoid is its peak / sqrt 2; per axis of 3
}

TEST(TrajectorySmoother, AShakenCameraIsSmoothedAgainstItsOwnAcceleration) {
  std::mt19937 rng(5);
  std::normal_distribution<double> noise(0.0, 0.003);
  std::vector<SmootherSample> s;
  double sum_before = 0.0;
  for (int i = 0; i < 300; ++i) {
    const double t = i / kFps;
    const Eigen::Vector3d n(noise(rng), noise(rng), noise(rng));
    s.push_back({t, shakenPathAt(t) + n, 0.003, false});
    sum_before += n.squaredNorm();
  }
  const double measured = measuredAccelSigma(s, 0, s.size(), SmootherOptions{}.accel_lag_s).value_or(0.0);
  // Second differences over 0.2 s see 87-94 % of these sinusoids' acceleration.
  EXPECT_GT(measured, 0.8 * shakenAccelSigma());
  EXPECT_LT(measured, 1.1 * shakenAccelSigma());

  auto rms = [&](const std::vector<Eigen::Vector3d>& p) {
    double sum = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) sum += (p[i] - shakenPathAt(s[i].stamp)).squaredNorm();
    return std::sqrt(sum / static_cast<double>(p.size()));
  };
  const double before = std::sqrt(sum_before / static_cast<double>(s.size()));
  EXPECT_LT(rms(smoothPositions(s, {})), 0.7 * before);

  // What the floor alone costs: the tracker's errors are not independent from frame to frame (a frame is
  // tied to its keyframe), so smoothing removes less of them than of white noise, while the camera's real
  // motion, smoothed away, is lost. Without noise that loss is all there is.
  for (auto& x : s) x.position = shakenPathAt(x.stamp);
  SmootherOptions fixed;
  fixed.accel_lag_s = 0.0;
  const double with_floor = rms(smoothPositions(s, fixed));
  const double with_measured = rms(smoothPositions(s, {}));
  EXPECT_LT(with_measured, 0.5 * with_floor) << with_floor << " -> " << with_measured;
}

TEST(TrajectorySmoother, AGentleCameraIsSmoothedAgainstTheFloor) {
  // The synthetic scenes' path (under 0.4 m/s^2) and 1 cm noise: the measurement stays under the floor, so
  // the result is the fixed floor's, exactly.
  const std::vector<SmootherSample> s = noisyPath(300, 0.01, 6);
  const auto gentle = measuredAccelSigma(s, 0, s.size(), SmootherOptions{}.accel_lag_s);
  ASSERT_TRUE(gentle);
  EXPECT_LT(*gentle, 0.5);
  SmootherOptions fixed;
  fixed.accel_lag_s = 0.0;
  const auto a = smoothPositions(s, fixed);
  const auto b = smoothPositions(s, {});
  for (std::size_t i = 0; i < s.size(); ++i) EXPECT_EQ(a[i], b[i]) << i;
  // Too short a stretch to measure, or not a stretch at all (every stamp the same): no measurement.
  EXPECT_FALSE(measuredAccelSigma(s, 0, 15, 0.2));
  std::vector<SmootherSample> same = s;
  for (auto& x : same) x.stamp = 1.0;
  EXPECT_FALSE(measuredAccelSigma(same, 0, same.size(), 0.2));
}

TEST(TrajectorySmoother, UniformMotionIsKeptExactlyAtAnySpacing) {
  // No acceleration, nothing to smooth: frames 1, 2 or 3 intervals apart (dropped frames) keep their place.
  std::vector<SmootherSample> s;
  double t = 0.0;
  for (int i = 0; i < 40; ++i) {
    t += (1 + i % 3) / kFps;
    s.push_back(
        {t, Eigen::Vector3d(0.5, -0.2, 0.1) * t + Eigen::Vector3d(1, 2, 3), 0.005 + 0.01 * (i % 4), false});
  }
  const auto p = smoothPositions(s, {});
  for (std::size_t i = 0; i < s.size(); ++i) EXPECT_LT((p[i] - s[i].position).norm(), 1e-9) << i;
}

TEST(TrajectorySmoother, AWellPinnedFrameStaysAndAWeakOneFollowsItsNeighbours) {
  std::vector<SmootherSample> s = noisyPath(120, 0.0, 2);  // on the path exactly
  for (auto& x : s) x.std_m = 0.003;
  // Frame 50 is pinned to 0.1 mm but 5 mm off the path; frame 80 is 5 cm off but weakly pinned (5 cm).
  s[50].position += Eigen::Vector3d(0.005, 0.0, 0.0);
  s[50].std_m = 0.0001;
  s[80].position += Eigen::Vector3d(0.0, 0.05, 0.0);
  s[80].std_m = 0.05;
  const auto p = smoothPositions(s, {});
  EXPECT_LT((p[50] - s[50].position).norm(), 0.0005);
  EXPECT_LT((p[80] - pathAt(s[80].stamp)).norm(), 0.005);
}

TEST(TrajectorySmoother, NoLinkAcrossALossAGapOrAStepBack) {
  // Two stretches of the same path 1 m apart, as after a relocalisation that corrected a drift.
  std::vector<SmootherSample> s = noisyPath(100, 0.005, 3);
  for (int i = 50; i < 100; ++i) s[i].position.x() += 1.0;
  std::vector<SmootherSample> first(s.begin(), s.begin() + 50), second(s.begin() + 50, s.end());
  const auto a = smoothPositions(first, {});
  const auto b = smoothPositions(second, {});
  auto expectStretches = [&](const std::vector<SmootherSample>& whole, const char* why) {
    const auto p = smoothPositions(whole, {});
    for (int i = 0; i < 100; ++i)
      EXPECT_LT((p[i] - (i < 50 ? a[i] : b[i - 50])).norm(), 1e-9) << why << ", frame " << i;
  };
  s[50].starts_stretch = true;
  expectStretches(s, "relocalised");
  s[50].starts_stretch = false;
  // Linked, the jump is spread over its neighbours: the case the break exists for.
  EXPECT_GT((smoothPositions(s, {})[49] - a[49]).norm(), 0.05);
  std::vector<SmootherSample> gap = s;
  for (int i = 50; i < 100; ++i) gap[i].stamp += 0.6;  // over max_gap_s (0.5)
  expectStretches(gap, "gap");
  std::vector<SmootherSample> back = s;
  for (int i = 50; i < 100; ++i) back[i].stamp -= 50.0 / kFps;  // a looped replay starts again
  expectStretches(back, "step back");
}

TEST(TrajectorySmoother, OffShortOrUnweighedStretchesAreLeftAsTheyAre) {
  const std::vector<SmootherSample> s = noisyPath(30, 0.01, 4);
  SmootherOptions off;
  off.accel_sigma = 0.0;
  const auto p = smoothPositions(s, off);
  for (std::size_t i = 0; i < s.size(); ++i) EXPECT_EQ(p[i], s[i].position);
  const std::vector<SmootherSample> two(s.begin(), s.begin() + 2);
  const auto q = smoothPositions(two, {});
  EXPECT_EQ(q[0], two[0].position);
  EXPECT_EQ(q[1], two[1].position);
  std::vector<SmootherSample> unknown = s;
  for (auto& x : unknown) x.std_m = std::numeric_limits<double>::infinity();
  const auto r = smoothPositions(unknown, {});
  for (std::size_t i = 0; i < s.size(); ++i) EXPECT_EQ(r[i], s[i].position);
  // One frame of unknown std among known ones is weighed as their median: smoothed like them.
  std::vector<SmootherSample> one = s;
  one[10].std_m = std::numeric_limits<double>::quiet_NaN();
  const auto with_unknown = smoothPositions(one, {});
  const auto all_known = smoothPositions(s, {});
  EXPECT_LT((with_unknown[10] - all_known[10]).norm(), 1e-9);
}

}  // namespace
}  // namespace bmp::tracker

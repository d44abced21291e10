#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include <Eigen/Eigenvalues>

#include "tracker/frame_pose.hpp"
#include "tracker/key_frame.hpp"
#include "tracker/map_point.hpp"
#include "tracker/motion_prior.hpp"
#include "tracker/pose_optimizer.hpp"

namespace bmp::tracker {
namespace {

TEST(TrackerPoseOptimizer, RecoversKnownPoseFromNoisyCorrespondencesWithOutliers) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> ux(-2.0, 2.0), uz(1.0, 5.0), upx(0.0, 640.0), upy(0.0, 480.0);
  std::normal_distribution<double> pixel_noise(0.0, 0.7);
  const PoseCamera cam{540.0, 540.0, 320.0, 240.0, 540.0 * 0.08};
  const SE3 T_cam_world_true =
      makeSE3(Eigen::Vector3d(0.3, -0.1, 0.5),
              Eigen::Quaterniond(Eigen::AngleAxisd(0.4, Eigen::Vector3d(0.2, 1, 0.1).normalized())));
  std::vector<PoseObservation> obs;
  std::vector<bool> is_outlier;
  for (int i = 0; i < 400; ++i) {
    const Eigen::Vector3d p_cam(ux(rng), ux(rng) * 0.75, uz(rng));
    PoseObservation o;
    o.p_world = T_cam_world_true.inverse() * p_cam;
    const bool outlier = i % 5 == 0;  // 20 %
    if (outlier) {
      o.uv = Eigen::Vector2d(upx(rng), upy(rng));
    } else {
      o.uv = Eigen::Vector2d(cam.fx * p_cam.x() / p_cam.z() + cam.cx + pixel_noise(rng),
                             cam.fy * p_cam.y() / p_cam.z() + cam.cy + pixel_noise(rng));
    }
    o.u_right = i % 2 == 0 ? o.uv.x() - cam.bf / p_cam.z() + pixel_noise(rng) : -1.0;  // half with depth
    o.information = 1.0;
    obs.push_back(o);
    is_outlier.push_back(outlier);
  }
  // Start 10 cm and about 6 degrees away.
  SE3 T = T_cam_world_true *
          makeSE3(Eigen::Vector3d(0.06, -0.05, 0.06),
                  Eigen::Quaterniond(Eigen::AngleAxisd(0.1, Eigen::Vector3d(1, 0.5, -0.3).normalized())));
  const int inliers = optimizePose(T, obs, cam, PoseOptimizerOptions{});

  const SE3 error = T * T_cam_world_true.inverse();
  EXPECT_LT(error.translation().norm(), 0.01);
  EXPECT_LT(rotationAngle(error), 0.2 * M_PI / 180.0);
  int caught = 0, false_alarms = 0;
  for (std::size_t i = 0; i < obs.size(); ++i) {
    if (is_outlier[i])
      caught += obs[i].outlier;
    else
      false_alarms += obs[i].outlier;
  }
  EXPECT_GE(caught, 78);        // of 80 outliers
  EXPECT_LE(false_alarms, 25);  // of 320 inliers (chi2 95 %: about 16 expected)
  EXPECT_EQ(inliers, 400 - caught - false_alarms);
}

TEST(TrackerPoseOptimizer, WeightZeroObservationsTakeNoPart) {
  const PoseCamera cam{500.0, 500.0, 320.0, 240.0, 40.0};
  std::vector<PoseObservation> obs;
  for (int i = 0; i < 50; ++i) {
    const int row = i / 10;
    const Eigen::Vector3d p(0.1 * (i % 10) - 0.5, 0.1 * row - 0.25, 2.0 + 0.05 * (i % 7));
    PoseObservation o;
    o.p_world = p;
    o.uv = Eigen::Vector2d(cam.fx * p.x() / p.z() + cam.cx, cam.fy * p.y() / p.z() + cam.cy);
    if (i < 20) {  // consistent with a different pose, but excluded by weight 0
      o.uv += Eigen::Vector2d(15.0, 0.0);
      o.weight = 0.0;
    }
    obs.push_back(o);
  }
  SE3 T = SE3::Identity();
  T.translation() = Eigen::Vector3d(0.01, 0.0, 0.0);
  EXPECT_EQ(optimizePose(T, obs, cam, PoseOptimizerOptions{}), 30);
  EXPECT_LT(T.translation().norm(), 1e-4);
}

// The solver is our own Levenberg-Marquardt: from 25 cm and 15 degrees off, with exact data and no
// outliers, it must land on the pose itself, mono-only and depth-only alike.
TEST(TrackerPoseOptimizer, ConvergesExactlyFromFarOffWithAndWithoutDepth) {
  const PoseCamera cam{525.0, 525.0, 319.5, 239.5, 525.0 * 0.08};
  const SE3 T_true =
      makeSE3(Eigen::Vector3d(-0.2, 0.1, 0.3),
              Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d(0.1, 1, 0).normalized())));
  for (const bool with_depth : {false, true}) {
    std::vector<PoseObservation> obs;
    for (int i = 0; i < 120; ++i) {
      const int row = i / 12;
      const Eigen::Vector3d p_cam(0.05 * (i % 12) - 0.3, 0.04 * row - 0.2, 1.5 + 0.1 * (i % 9));
      PoseObservation o;
      o.p_world = T_true.inverse() * p_cam;
      o.uv =
          Eigen::Vector2d(cam.fx * p_cam.x() / p_cam.z() + cam.cx, cam.fy * p_cam.y() / p_cam.z() + cam.cy);
      if (with_depth) o.u_right = o.uv.x() - cam.bf / p_cam.z();
      obs.push_back(o);
    }
    SE3 T = T_true *
            makeSE3(Eigen::Vector3d(0.15, -0.1, 0.17),
                    Eigen::Quaterniond(Eigen::AngleAxisd(0.26, Eigen::Vector3d(1, 0.2, 0.4).normalized())));
    PoseOptimizerOptions options;
    options.iterations_per_round = 20;
    EXPECT_EQ(optimizePose(T, obs, cam, options), 120) << with_depth;
    const SE3 error = T * T_true.inverse();
    EXPECT_LT(error.translation().norm(), 1e-6) << with_depth;
    EXPECT_LT(rotationAngle(error), 1e-6) << with_depth;
  }
}

// A point behind the camera must neither break the solve nor count as an inlier.
TEST(TrackerPoseOptimizer, PointBehindTheCameraIsAnOutlier) {
  const PoseCamera cam{500.0, 500.0, 320.0, 240.0, 40.0};
  std::vector<PoseObservation> obs;
  for (int i = 0; i < 40; ++i) {
    const int row = i / 8;
    const Eigen::Vector3d p(0.1 * (i % 8) - 0.4, 0.1 * row - 0.2, 2.0 + 0.1 * (i % 5));
    PoseObservation o;
    o.p_world = p;
    o.uv = Eigen::Vector2d(cam.fx * p.x() / p.z() + cam.cx, cam.fy * p.y() / p.z() + cam.cy);
    obs.push_back(o);
  }
  PoseObservation behind;
  behind.p_world = Eigen::Vector3d(0.1, 0.1, -1.0);
  behind.uv = Eigen::Vector2d(300.0, 200.0);
  obs.push_back(behind);
  SE3 T = SE3::Identity();
  T.translation() = Eigen::Vector3d(0.02, -0.01, 0.03);
  EXPECT_EQ(optimizePose(T, obs, cam, PoseOptimizerOptions{}), 40);
  EXPECT_TRUE(obs.back().outlier);
  EXPECT_LT(T.translation().norm(), 1e-6);
}

// A point counts fully in the pose once enough keyframes saw it, spread over enough time: keyframes come
// fast while people fill the view, and a walking person's points must not mature in a fraction of a second.
TEST(TrackerPoseOptimizer, PointMaturesByKeyframesAndTimeSpan) {
  PoseOptimizerOptions options;
  options.mature_observations = 3;
  options.mature_span_s = 1.0;
  std::vector<std::shared_ptr<KeyFrame>> kfs;
  for (int k = 0; k < 4; ++k)
    kfs.push_back(std::make_shared<KeyFrame>(k, Frame(k, 10.0 + 0.4 * k, std::make_shared<Features>())));
  MapPoint mp(0, Eigen::Vector3d(0, 0, 2), cv::Mat::zeros(1, 32, CV_8U), 0);
  mp.observations[kfs[0].get()] = 0;
  mp.observations[kfs[1].get()] = 0;
  EXPECT_FALSE(isMature(mp, options));  // two keyframes
  mp.observations[kfs[2].get()] = 0;
  EXPECT_FALSE(isMature(mp, options));  // three, but within 0.8 s
  mp.observations[kfs[3].get()] = 0;
  EXPECT_TRUE(isMature(mp, options));  // four over 1.2 s
  options.mature_span_s = 0.0;
  mp.observations.erase(kfs[3].get());
  EXPECT_TRUE(isMature(mp, options));  // span check off: three keyframes are enough

  // A temporary point (no keyframe saw it) is never mature, however the rule is set.
  const MapPoint temporary(-1, Eigen::Vector3d(0, 0, 2), cv::Mat::zeros(1, 32, CV_8U), -1);
  for (const int min_kfs : {0, 3})
    for (const double span : {0.0, 1.0}) {
      options.mature_observations = min_kfs;
      options.mature_span_s = span;
      EXPECT_EQ(isMature(temporary, options), min_kfs == 0 && span == 0.0) << min_kfs << " " << span;
    }
}

// A scene at one depth (a wall 3 m away, no depth measured): a sideways shift with a turn that keeps the
// wall in place is barely seen by the keypoints, so each solve lands somewhere along it. A prior on the
// position (here at the true one, as a good prediction would be) holds it.
Eigen::Vector3d wallPositionError(std::mt19937& rng, const PositionPrior* prior) {
  std::uniform_real_distribution<double> ux(-1.5, 1.5);
  std::normal_distribution<double> pixel_noise(0.0, 1.0);
  const PoseCamera cam{540.0, 540.0, 320.0, 240.0, 540.0 * 0.08};
  std::vector<PoseObservation> obs;
  for (int i = 0; i < 300; ++i) {
    const Eigen::Vector3d p(ux(rng), ux(rng) * 0.75, 3.0);  // world = true camera frame
    PoseObservation o;
    o.p_world = p;
    o.uv = Eigen::Vector2d(cam.fx * p.x() / p.z() + cam.cx + pixel_noise(rng),
                           cam.fy * p.y() / p.z() + cam.cy + pixel_noise(rng));
    obs.push_back(o);
  }
  SE3 T = makeSE3(Eigen::Vector3d(0.01, 0.0, 0.0), Eigen::Quaterniond::Identity());
  optimizePose(T, obs, cam, PoseOptimizerOptions{}, prior);
  return -(T.rotation().transpose() * T.translation());  // the camera centre; truly at the origin
}

TEST(TrackerPoseOptimizer, PositionPriorHoldsTheShiftWithATurnThatKeypointsBarelySee) {
  std::mt19937 rng(3);
  // Information adds: a 2 mm prior on a position loose by about 7 mm leaves about 2 mm.
  const PositionPrior prior{Eigen::Vector3d::Zero(), 0.002};
  double free_sq = 0.0, held_sq = 0.0;
  constexpr int kTrials = 40;
  for (int t = 0; t < kTrials; ++t) {
    std::mt19937 same = rng;  // the same keypoints and noise for both
    free_sq += wallPositionError(rng, nullptr).squaredNorm();
    held_sq += wallPositionError(same, &prior).squaredNorm();
  }
  const double free_rms = std::sqrt(free_sq / kTrials), held_rms = std::sqrt(held_sq / kTrials);
  EXPECT_GT(free_rms, 0.005) << "the scene should leave the position loose";
  EXPECT_LT(held_rms, 0.5 * free_rms);
}

// A prediction the keypoints clearly contradict (the camera did accelerate) is dropped, not followed.
TEST(TrackerPoseOptimizer, PositionPriorThePoseCannotMeetIsDropped) {
  std::mt19937 rng(5);
  const PositionPrior far_off{Eigen::Vector3d(0.10, 0.0, 0.05), 0.008};
  std::mt19937 same = rng;
  const Eigen::Vector3d free = wallPositionError(rng, nullptr);
  const Eigen::Vector3d gated = wallPositionError(same, &far_off);
  EXPECT_LT((gated - free).norm(), 1e-6);
}

// Keypoints with depth at 1 px noise, in the true camera frame (world = camera, centre at the origin):
// `count` points at 4-5 m in a band at the top of the image (what a crowd in front leaves of a room), or
// spread over the view at 1-5 m.
std::vector<PoseObservation> scenePoints(std::mt19937& rng, int count, bool band, const PoseCamera& cam) {
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  std::normal_distribution<double> pixel_noise(0.0, 1.0);
  std::vector<PoseObservation> obs;
  for (int i = 0; i < count; ++i) {
    const double z = band ? 4.0 + u01(rng) : 1.0 + 4.0 * u01(rng);
    const double u = 640.0 * u01(rng), v = band ? 100.0 * u01(rng) : 480.0 * u01(rng);
    const Eigen::Vector3d p((u - cam.cx) * z / cam.fx, (v - cam.cy) * z / cam.fy, z);
    PoseObservation o;
    o.p_world = p;
    o.uv = Eigen::Vector2d(u + pixel_noise(rng), v + pixel_noise(rng));
    o.u_right = o.uv.x() - cam.bf / z + pixel_noise(rng);
    obs.push_back(o);
  }
  return obs;
}

Eigen::Vector3d centre(const SE3& T_cam_world) {
  return -(T_cam_world.rotation().transpose() * T_cam_world.translation());
}

// The figure is what the pose's own spread turns out to be: solved again and again with fresh noise, the
// camera centre scatters along its worst direction by about the predicted standard deviation.
TEST(TrackerPoseOptimizer, PositionStdIsTheSpreadOfTheSolvedPosition) {
  const PoseCamera cam{525.0, 525.0, 319.5, 239.5, 525.0 * 0.08};
  std::mt19937 rng(11);
  constexpr int kTrials = 200;
  std::vector<Eigen::Vector3d> centres;
  double predicted = 0.0;
  for (int t = 0; t < kTrials; ++t) {
    std::vector<PoseObservation> obs = scenePoints(rng, 150, true, cam);
    SE3 T = SE3::Identity();
    optimizePose(T, obs, cam, PoseOptimizerOptions{});
    centres.push_back(centre(T));
    predicted += positionStd(T, obs, cam) / kTrials;
  }
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& c : centres) mean += c / kTrials;
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const auto& c : centres) cov += (c - mean) * (c - mean).transpose() / (kTrials - 1);
  const double measured = std::sqrt(Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(cov).eigenvalues()(2));
  std::printf("far band, 150 points: predicted %.1f mm, measured over %d solves %.1f mm\n", predicted * 1e3,
              kTrials, measured * 1e3);
  EXPECT_GT(measured, 0.75 * predicted);
  EXPECT_LT(measured, 1.33 * predicted);
}

// A far band pins the position several times worse than the same number of keypoints over the view, and
// four times the keypoints halve it.
TEST(TrackerPoseOptimizer, PositionStdGrowsWhenTheStaticPointsAreAFarBand) {
  const PoseCamera cam{525.0, 525.0, 319.5, 239.5, 525.0 * 0.08};
  std::mt19937 rng(12);
  const SE3 truth = SE3::Identity();
  const double band = positionStd(truth, scenePoints(rng, 150, true, cam), cam);
  const double spread = positionStd(truth, scenePoints(rng, 150, false, cam), cam);
  const double band_x4 = positionStd(truth, scenePoints(rng, 600, true, cam), cam);
  std::printf("150 points: far band %.1f mm, over the view %.1f mm; 600 in the band %.1f mm\n", band * 1e3,
              spread * 1e3, band_x4 * 1e3);
  EXPECT_GT(band, 3.0 * spread);
  EXPECT_NEAR(band_x4 / band, 0.5, 0.1);
}

TEST(TrackerPoseOptimizer, PositionStdCountsInliersOnlyAndNeedsThree) {
  const PoseCamera cam{525.0, 525.0, 319.5, 239.5, 525.0 * 0.08};
  std::mt19937 rng(13);
  std::vector<PoseObservation> obs = scenePoints(rng, 100, false, cam);
  const double all = positionStd(SE3::Identity(), obs, cam);
  for (std::size_t i = 50; i < obs.size(); ++i) obs[i].outlier = true;
  const double half = positionStd(SE3::Identity(), obs, cam);
  EXPECT_GT(half, 1.2 * all);
  for (std::size_t i = 2; i < 50; ++i) obs[i].outlier = true;
  EXPECT_TRUE(std::isinf(positionStd(SE3::Identity(), obs, cam)));
}

TEST(MotionPrior, PredictsFromTheSmoothedVelocityWithinHalfAccelerationTimesDtSquared) {
  PoseOptimizerOptions options;
  options.motion_prior_accel = 10.0;
  options.motion_prior_velocity_gain = 0.5;
  options.motion_prior_accel_lag_s = 0.0;  // the floor always (the measured spread: the test below)
  MotionPrior motion(options);
  EXPECT_FALSE(motion.predict(Eigen::Vector3d::Zero(), 0.1)) << "no velocity yet";
  motion.observe(Eigen::Vector3d::Zero(), 0.1, {0.1, Eigen::Vector3d(0.1, 0, 0), 0.001, false});  // 1 m/s
  motion.observe(Eigen::Vector3d(0.1, 0, 0), 0.1,
                 {0.2, Eigen::Vector3d(0.4, 0, 0), 0.001, false});  // 3: to 2
  const auto prior = motion.predict(Eigen::Vector3d(0.4, 0, 0), 0.05);
  ASSERT_TRUE(prior);
  EXPECT_NEAR((prior->center - Eigen::Vector3d(0.5, 0, 0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR(prior->sigma_m, 0.5 * 10.0 * 0.05 * 0.05, 1e-12);
  motion.reset();
  EXPECT_FALSE(motion.predict(Eigen::Vector3d::Zero(), 0.05));
  options.motion_prior_accel = 0.0;  // off
  MotionPrior off(options);
  off.observe(Eigen::Vector3d::Zero(), 0.1, {0.1, Eigen::Vector3d(0.1, 0, 0), 0.001, false});
  EXPECT_FALSE(off.predict(Eigen::Vector3d::Zero(), 0.05));
}

// A camera moving along sinusoids of 1-1.6 s periods per axis (amplitude_m each), tracked at 30 Hz with
// 2 mm noise: how many of the frames after the first window the prediction misses by more than 3 sigma on
// some axis, and the acceleration the spread stood for at the end.
struct PriorOnSinusoids {
  double missed_share = 0.0;
  double accel = 0.0;
};

PriorOnSinusoids priorOnSinusoids(const PoseOptimizerOptions& options, double amplitude_m) {
  const Eigen::Vector3d omega(2.0 * M_PI / 1.0, 2.0 * M_PI / 1.3, 2.0 * M_PI / 1.6);
  auto at = [&](double t) {
    return Eigen::Vector3d(amplitude_m * std::sin(omega.x() * t), amplitude_m * std::sin(omega.y() * t + 1.0),
                           amplitude_m * std::sin(omega.z() * t + 2.0));
  };
  std::mt19937 rng(5);
  std::normal_distribution<double> noise(0.0, 0.002);
  MotionPrior motion(options);
  const double dt = 1.0 / 30.0;
  Eigen::Vector3d last = at(0.0);
  int judged = 0, missed = 0;
  for (int i = 1; i < 150; ++i) {
    const double t = i * dt;
    const Eigen::Vector3d truth = at(t);
    const auto prior = motion.predict(last, dt);
    if (t > options.motion_prior_accel_window_s && prior) {
      ++judged;
      missed += ((truth - prior->center).cwiseAbs().array() > 3.0 * prior->sigma_m).any();
    }
    const Eigen::Vector3d tracked = truth + Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
    motion.observe(last, dt, {t, tracked, 0.002, false});
    last = tracked;
  }
  return {judged > 0 ? static_cast<double>(missed) / judged : 1.0, motion.accel()};
}

// A shaken camera (5 m/s^2 RMS here) is missed by the smoothed-velocity prediction by far more than the
// floor's spread: held to it, the tracker was pulled off its path (shaken_camera: 11 cm). Its measured
// acceleration widens the spread to what the prediction misses by; a gentle camera keeps the floor exactly.
TEST(MotionPrior, ACameraShakenHarderThanTheFloorWidensTheSpreadToItsMisses) {
  PoseOptimizerOptions options;  // the defaults: 9 m/s^2 floor, gain 0.3, measured over 0.2 s in 1.5 s
  PoseOptimizerOptions floor_only = options;
  floor_only.motion_prior_accel_lag_s = 0.0;
  const PriorOnSinusoids held = priorOnSinusoids(floor_only, 0.15);
  const PriorOnSinusoids measured = priorOnSinusoids(options, 0.15);
  EXPECT_DOUBLE_EQ(held.accel, options.motion_prior_accel);
  EXPECT_GT(held.missed_share, 0.3);
  EXPECT_GT(measured.accel, 1.5 * options.motion_prior_accel);
  EXPECT_LT(measured.missed_share, 0.05) << held.missed_share;
  // 1 cm sinusoids: about 0.6 m/s^2, well under the floor, which is kept as it is.
  const PriorOnSinusoids gentle = priorOnSinusoids(options, 0.01);
  EXPECT_DOUBLE_EQ(gentle.accel, options.motion_prior_accel);
  EXPECT_LT(gentle.missed_share, 0.05);

  // Before the window holds frames enough, the camera's motion is not known: the spread is the unmeasured
  // one, and after a loss (reset) it is again.
  MotionPrior motion(options);
  for (int i = 1; i <= 20; ++i)
    motion.observe(Eigen::Vector3d::Zero(), 1.0 / 30.0, {i / 30.0, Eigen::Vector3d::Zero(), 0.002, false});
  EXPECT_DOUBLE_EQ(motion.accel(), options.motion_prior_accel_unmeasured);
  for (int i = 21; i <= 60; ++i)
    motion.observe(Eigen::Vector3d::Zero(), 1.0 / 30.0, {i / 30.0, Eigen::Vector3d::Zero(), 0.002, false});
  EXPECT_DOUBLE_EQ(motion.accel(), options.motion_prior_accel);
  motion.reset();
  motion.observe(Eigen::Vector3d::Zero(), 1.0 / 30.0, {3.0, Eigen::Vector3d::Zero(), 0.002, false});
  EXPECT_DOUBLE_EQ(motion.accel(), options.motion_prior_accel_unmeasured);
}

}  // namespace
}  // namespace bmp::tracker

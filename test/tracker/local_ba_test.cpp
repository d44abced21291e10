#include <gtest/gtest.h>

#include <random>

#include "tracker/local_ba.hpp"

namespace bmp::tracker {
namespace {

double poseError(const SE3& a, const SE3& b) {
  return (a.inverse().translation() - b.inverse().translation()).norm();
}

TEST(TrackerLocalBa, ReducesTheErrorOfPerturbedKeyframes) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> ux(-2.0, 2.0), uz(2.0, 5.0);
  std::normal_distribution<double> noise(0.0, 0.5), shift(0.0, 0.03), turn(0.0, 0.01), blur(0.0, 0.03);
  const PoseCamera cam{540.0, 540.0, 320.0, 240.0, 540.0 * 0.08};
  // Six keyframes moving sideways along x, looking along z; points spread in front of them.
  std::vector<SE3> truth;
  for (int k = 0; k < 6; ++k) {
    SE3 T_world_cam = makeSE3(Eigen::Vector3d(0.15 * k, 0.02 * k, 0.0),
                              Eigen::Quaterniond(Eigen::AngleAxisd(0.03 * k, Eigen::Vector3d::UnitY())));
    truth.push_back(T_world_cam.inverse());
  }
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 300; ++i) points.emplace_back(ux(rng) + 0.4, ux(rng) * 0.7, uz(rng));

  BaProblem ba;
  for (int k = 0; k < 6; ++k) {
    BaKeyFrame kf;
    kf.id = k;
    kf.fixed = k < 2;
    kf.T_cam_world = truth[k];
    if (!kf.fixed)
      kf.T_cam_world = makeSE3(Eigen::Vector3d(shift(rng), shift(rng), shift(rng)),
                               Eigen::Quaterniond(Eigen::AngleAxisd(turn(rng), Eigen::Vector3d::UnitX()) *
                                                  Eigen::AngleAxisd(turn(rng), Eigen::Vector3d::UnitY()))) *
                       truth[k];
    ba.keyframes.push_back(kf);
  }
  for (std::size_t i = 0; i < points.size(); ++i)
    ba.points.push_back(
        {static_cast<int64_t>(i), points[i] + Eigen::Vector3d(blur(rng), blur(rng), blur(rng))});
  int outliers_planted = 0;
  for (int k = 0; k < 6; ++k) {
    for (std::size_t i = 0; i < points.size(); ++i) {
      const Eigen::Vector3d p = truth[k] * points[i];
      BaObservation o;
      o.keyframe = k;
      o.point = static_cast<int>(i);
      o.uv = Eigen::Vector2d(cam.fx * p.x() / p.z() + cam.cx + noise(rng),
                             cam.fy * p.y() / p.z() + cam.cy + noise(rng));
      o.u_right = o.uv.x() - cam.bf / p.z() + noise(rng);
      if (i % 50 == 7 && k == 3) {  // a few gross mismatches
        o.uv += Eigen::Vector2d(30.0, -20.0);
        ++outliers_planted;
      }
      ba.observations.push_back(o);
    }
  }
  double before = 0.0;
  for (int k = 2; k < 6; ++k) before += poseError(ba.keyframes[k].T_cam_world, truth[k]);
  const BaSummary summary = solveLocalBa(ba, cam, MappingOptions{}, PoseOptimizerOptions{});
  double after = 0.0;
  for (int k = 2; k < 6; ++k) after += poseError(ba.keyframes[k].T_cam_world, truth[k]);

  EXPECT_LT(summary.final_cost, summary.initial_cost);
  EXPECT_LT(after, before / 5.0) << "before " << before << " after " << after;
  EXPECT_LT(after / 4.0, 0.005);  // mean keyframe position error under 5 mm
  for (int k = 0; k < 2; ++k)
    EXPECT_TRUE(ba.keyframes[k].T_cam_world.isApprox(truth[k])) << "fixed keyframe " << k << " moved";
  int flagged = 0;
  for (const auto& o : ba.observations) flagged += o.outlier;
  EXPECT_GE(flagged, outliers_planted);
}

// Points that moved between the keyframes (a person walking) with young-point weight barely move the
// keyframe; at full weight they drag it along. Local mapping gives unproven points that weight (isMature).
TEST(TrackerLocalBa, DownWeightedMovingPointsDoNotPullTheKeyframe) {
  const PoseCamera cam{540.0, 540.0, 320.0, 240.0, 540.0 * 0.08};
  const SE3 T0 = SE3::Identity();
  const SE3 T1 = makeSE3(Eigen::Vector3d(-0.1, 0.0, 0.0), Eigen::Quaterniond::Identity());  // camera moved +x
  const Eigen::Vector3d walk(0.015, 0.0, 0.0);  // the walker's points moved 1.5 cm between the keyframes
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> ux(-1.5, 1.5), uz(2.5, 4.0);
  const auto solve = [&](double walker_weight) {
    BaProblem ba;
    ba.keyframes.push_back({0, T0, true});
    ba.keyframes.push_back({1, T1, false});
    std::mt19937 local(rng);
    for (int i = 0; i < 300; ++i) {
      const bool walker = i % 2 == 1;
      const Eigen::Vector3d p(ux(local), ux(local) * 0.6, uz(local));
      ba.points.push_back({i, p});
      for (int k = 0; k < 2; ++k) {
        const Eigen::Vector3d seen = (k == 0 ? T0 : T1) * (walker && k == 1 ? Eigen::Vector3d(p + walk) : p);
        BaObservation o;
        o.keyframe = k;
        o.point = i;
        o.uv = Eigen::Vector2d(cam.fx * seen.x() / seen.z() + cam.cx, cam.fy * seen.y() / seen.z() + cam.cy);
        o.u_right = o.uv.x() - cam.bf / seen.z();
        o.weight = walker ? walker_weight : 1.0;
        ba.observations.push_back(o);
      }
    }
    solveLocalBa(ba, cam, MappingOptions{}, PoseOptimizerOptions{});
    return poseError(ba.keyframes[1].T_cam_world, T1);
  };
  const double full = solve(1.0), young = solve(PoseOptimizerOptions{}.young_point_weight);
  // Measured: full weight 14.8 mm (the keyframe follows the walk), young weight 3.3 mm (what is left lies
  // along the weakly observed rotation/translation direction of two nearby views).
  EXPECT_GT(full, 0.010) << "at full weight the walker should drag the keyframe";
  EXPECT_LT(young, 0.35 * full) << "young " << young << " full " << full;
  EXPECT_LT(young, 0.005);
}

}  // namespace
}  // namespace bmp::tracker

// The trajectory's second look at each frame (frame_refiner.hpp): the pose against the points as they stand
// now, what it leaves out, and when each waiting frame gets it.
#include <gtest/gtest.h>

#include <random>

#include "tracker/frame_refiner.hpp"
#include "tracker/map_point.hpp"

namespace bmp::tracker {
namespace {

const PoseCamera kCamera{525.0, 525.0, 319.5, 239.5, 525.0 * 0.08};

struct Scene {
  std::vector<std::shared_ptr<MapPoint>> points;
  std::vector<RefineObservation> observations;
};

// n points in front of the camera at T_world_cam, observed without noise (with depth on every other one).
Scene sceneSeenFrom(const SE3& T_world_cam, int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> ux(-1.5, 1.5), uz(1.0, 5.0);
  Scene s;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d p_cam(ux(rng), ux(rng) * 0.75, uz(rng));
    auto mp = std::make_shared<MapPoint>(i, T_world_cam * p_cam, cv::Mat::zeros(1, 32, CV_8U), 0);
    const Eigen::Vector2d uv(kCamera.fx * p_cam.x() / p_cam.z() + kCamera.cx,
                             kCamera.fy * p_cam.y() / p_cam.z() + kCamera.cy);
    RefineObservation o;
    o.point = mp;
    o.uv = uv.cast<float>();
    o.u_right = i % 2 == 0 ? static_cast<float>(uv.x() - kCamera.bf / p_cam.z()) : -1.0f;
    s.points.push_back(mp);
    s.observations.push_back(o);
  }
  return s;
}

const SE3 kTrue =
    makeSE3(Eigen::Vector3d(0.4, -0.2, 1.1),
            Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d(0.1, 1, 0.2).normalized())));
// A tracked pose 2 cm and about a third of a degree off: what a frame carries against a map BA later moved.
const SE3 kTracked =
    kTrue * makeSE3(Eigen::Vector3d(0.012, -0.01, 0.012),
                    Eigen::Quaterniond(Eigen::AngleAxisd(0.006, Eigen::Vector3d(1, 0.5, -0.3).normalized())));

TEST(FrameRefiner, ReestimatesTheFrameAgainstThePointsAsTheyStandNow) {
  const Scene s = sceneSeenFrom(kTrue, 200, 3);
  const std::optional<SE3> refined = refineFramePose(kTracked, s.observations, kCamera, {}, 0.5, 30);
  ASSERT_TRUE(refined);
  const SE3 error = refined->inverse() * kTrue;
  EXPECT_LT(error.translation().norm(), 1e-4);
  EXPECT_LT(rotationAngle(error), 1e-5);
}

TEST(FrameRefiner, PointsCulledOrFoundMovingSinceTakeNoPart) {
  Scene s = sceneSeenFrom(kTrue, 200, 4);
  // 60 points moved 2 cm since the frame saw them, a few pixels, within the outlier test: culled (30) or
  // found on a mover (30). Taken into the pose they would pull it off; left out, the other 140 give the
  // true pose.
  for (int i = 0; i < 60; ++i) {
    s.points[i]->p_world += Eigen::Vector3d(0.02, 0.0, 0.0);
    if (i < 30)
      s.points[i]->bad = true;
    else
      s.points[i]->moving_probability = 0.9f;
  }
  // A point the map has dropped altogether.
  s.points[60].reset();
  const std::optional<SE3> refined = refineFramePose(kTracked, s.observations, kCamera, {}, 0.5, 30);
  ASSERT_TRUE(refined);
  EXPECT_LT((refined->inverse() * kTrue).translation().norm(), 1e-4);
  // With no threshold the 30 moving points count, and the pose goes with them.
  const std::optional<SE3> pulled = refineFramePose(kTracked, s.observations, kCamera, {}, 1.0, 30);
  ASSERT_TRUE(pulled);
  EXPECT_GT((pulled->inverse() * kTrue).translation().norm(), 3e-4);
}

TEST(FrameRefiner, TheFrameBetweenItsNeighboursIsExpectedOnTheLineBetweenThemAtItsTime) {
  const Eigen::Vector3d c0(1.0, 2.0, 3.0), c1(1.3, 2.0, 2.7);
  const std::optional<PositionPrior> mid = betweenNeighbours(10.0, c0, 10.1, 10.3, c1, 9.0);
  ASSERT_TRUE(mid);
  EXPECT_LT((mid->center - Eigen::Vector3d(1.1, 2.0, 2.9)).norm(), 1e-12);
  // An unknown acceleration of 9 m/s^2 takes it off that line by 9 / 2 x 0.1 s x 0.2 s = 9 cm at most.
  EXPECT_NEAR(mid->sigma_m, 0.09, 1e-12);
  // Neighbours 1/30 s either side (no frame dropped): 5 mm.
  EXPECT_NEAR(betweenNeighbours(0.0, c0, 1.0 / 30, 2.0 / 30, c1, 9.0)->sigma_m, 0.005, 1e-12);
  EXPECT_FALSE(betweenNeighbours(10.0, c0, 10.1, 10.1, c1, 9.0));  // not between them
  EXPECT_FALSE(betweenNeighbours(10.2, c0, 10.1, 10.3, c1, 9.0));
  EXPECT_FALSE(betweenNeighbours(10.0, c0, 10.1, 10.3, c1, 0.0));  // the motion prior is off
}

TEST(FrameRefiner, APriorBetweenTheNeighboursHoldsAFrameWithFewNoisyPoints) {
  // 60 points seen with 1 px of noise: alone they leave the frame a few millimetres off.
  Scene s = sceneSeenFrom(kTrue, 60, 5);
  std::mt19937 rng(6);
  std::normal_distribution<float> noise(0.0f, 1.0f);
  for (auto& o : s.observations) {
    const float du = noise(rng), dv = noise(rng);
    o.uv += Eigen::Vector2f(du, dv);
    if (o.u_right >= 0) o.u_right += du;
  }
  const auto off = [&](const std::optional<SE3>& T) {
    return (T->translation() - kTrue.translation()).norm();
  };
  const std::optional<SE3> alone = refineFramePose(kTracked, s.observations, kCamera, {}, 0.5, 30);
  ASSERT_TRUE(alone);
  EXPECT_GT(off(alone), 2e-3);
  // The neighbours say where it is within 2 mm (1 mm off the truth; frames 1/47 s apart at 9 m/s^2): the
  // frame ends nearer.
  const PositionPrior near{kTrue.translation() + Eigen::Vector3d(0.001, 0.0, 0.0), 0.002};
  const std::optional<SE3> held = refineFramePose(kTracked, s.observations, kCamera, {}, 0.5, 30, &near);
  ASSERT_TRUE(held);
  EXPECT_LT(off(held), 0.75 * off(alone)) << off(held);
  // Neighbours that disagree with the points by far more than the prior allows (the camera did jolt) are
  // not followed: the frame is solved by its points alone.
  const PositionPrior far{kTrue.translation() + Eigen::Vector3d(0.1, 0.0, 0.0), 0.002};
  const std::optional<SE3> jolted = refineFramePose(kTracked, s.observations, kCamera, {}, 0.5, 30, &far);
  ASSERT_TRUE(jolted);
  EXPECT_LT((jolted->translation() - alone->translation()).norm(), 1e-6);
}

TEST(FrameRefiner, KeepsTheTrackedPoseWhenTooFewPointsAgree) {
  Scene few = sceneSeenFrom(kTrue, 20, 5);
  EXPECT_FALSE(refineFramePose(kTracked, few.observations, kCamera, {}, 0.5, 30));
  // Enough points, but most of them moved since (the map changed under the frame): no new pose.
  Scene moved = sceneSeenFrom(kTrue, 100, 6);
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> shift(-0.3, 0.3);
  for (int i = 0; i < 70; ++i)
    moved.points[i]->p_world += Eigen::Vector3d(shift(rng), shift(rng), shift(rng));
  EXPECT_FALSE(refineFramePose(kTracked, moved.observations, kCamera, {}, 0.5, 30));
}

std::vector<std::size_t> takeDue(FrameRefiner& refiner, int64_t keyframes_made, bool all = false) {
  std::vector<std::size_t> records;
  refiner.takeDue(keyframes_made, all, [&](const FrameRefiner::Pending& p) { records.push_back(p.record); });
  return records;
}

TEST(FrameRefiner, EachFrameWaitsUntilItsKeyframeHasSettledThenGoesOldestFirstAFewAtATime) {
  RefineOptions options;
  options.after_keyframes = 2;
  options.per_frame = 2;
  options.max_pending = 100;
  FrameRefiner refiner(options);
  for (std::size_t r = 0; r < 5; ++r) refiner.add({r, 1, {}});  // tracked after keyframe 1 ...
  refiner.add({5, 2, {}});                                      // ... and one after keyframe 2
  EXPECT_TRUE(takeDue(refiner, 2).empty());                     // keyframe 1 still in local BA
  EXPECT_EQ(takeDue(refiner, 3), (std::vector<std::size_t>{0, 1}));
  EXPECT_EQ(takeDue(refiner, 3), (std::vector<std::size_t>{2, 3}));
  EXPECT_EQ(takeDue(refiner, 3), (std::vector<std::size_t>{4}));  // record 5's keyframe is 1 old
  EXPECT_EQ(refiner.pending(), 1u);
  // The end of the run: record 5's keyframe never settled, so it keeps its tracked pose and is let go.
  EXPECT_TRUE(takeDue(refiner, 3, true).empty());
  EXPECT_EQ(refiner.pending(), 0u);
  // Settled frames still waiting at the end all get their look, however many.
  for (std::size_t r = 6; r < 10; ++r) refiner.add({r, 3, {}});
  EXPECT_EQ(takeDue(refiner, 5, true), (std::vector<std::size_t>{6, 7, 8, 9}));
}

TEST(FrameRefiner, ACameraThatMakesNoKeyframeDoesNotHoldFramesWithoutBound) {
  RefineOptions options;
  options.after_keyframes = 5;
  options.max_pending = 3;
  FrameRefiner refiner(options);
  for (std::size_t r = 0; r < 6; ++r) refiner.add({r, 0, {}});
  // Over the bound the oldest are let go with their tracked pose: no keyframe, no BA under them.
  EXPECT_TRUE(takeDue(refiner, 0).empty());
  EXPECT_EQ(refiner.pending(), 3u);
  EXPECT_EQ(takeDue(refiner, 5), (std::vector<std::size_t>{3, 4}));
}

TEST(FrameRefiner, OffKeepsNothing) {
  RefineOptions options;
  options.after_keyframes = 0;
  FrameRefiner refiner(options);
  refiner.add({0, 0, {}});
  EXPECT_EQ(refiner.pending(), 0u);
  EXPECT_TRUE(takeDue(refiner, 10, true).empty());
}

}  // namespace
}  // namespace bmp::tracker

#include <gtest/gtest.h>

#include <fstream>

#include "bmp/common/tum_trajectory.hpp"
#include "shared_data.hpp"

namespace bmp {
namespace {

TEST(TumTrajectory, ReadsBonnGroundTruth) {
  const Trajectory gt = readTumTrajectory(test::bonnDir() + "/groundtruth.txt");
  ASSERT_EQ(gt.size(), 933u);
  EXPECT_NEAR(gt.front().stamp, 1548339819.89427, 1e-6);
  EXPECT_NEAR(gt.front().T_world_cam.translation().x(), -0.194787, 1e-9);
}

TEST(TumTrajectory, WriteReadRoundTrip) {
  Trajectory t;
  for (int i = 0; i < 5; ++i)
    t.push_back({1000.0 + i * 0.033333,
                 makeSE3({0.1 * i, -0.2, 1.0 + i},
                         Eigen::Quaterniond(Eigen::AngleAxisd(0.1 * i, Eigen::Vector3d::UnitY())))});
  const auto path = test::scratchDir("tum_traj") / "t.txt";
  writeTumTrajectory(path.string(), t);
  const Trajectory r = readTumTrajectory(path.string());
  ASSERT_EQ(r.size(), t.size());
  for (std::size_t i = 0; i < t.size(); ++i) {
    EXPECT_NEAR(r[i].stamp, t[i].stamp, 1e-6);
    EXPECT_LT((r[i].T_world_cam.matrix() - t[i].T_world_cam.matrix()).norm(), 1e-6);
  }
}

TEST(TumTrajectory, MalformedLineNamesFileAndLine) {
  try {
    parseTumTrajectory("# c\n1.0 0 0 0 0 0 0 1\n2.0 0 0 zero 0 0 0 1\n", "est.txt");
    FAIL();
  } catch (const TrajectoryError& e) {
    EXPECT_NE(std::string(e.what()).find("est.txt:3"), std::string::npos) << e.what();
  }
  EXPECT_THROW(parseTumTrajectory("1.0 0 0 0 0 0 0\n", "short.txt"), TrajectoryError);
  EXPECT_THROW(parseTumTrajectory("1.0 0 0 0 0 0 0 0\n", "zeroquat.txt"), TrajectoryError);
  EXPECT_EQ(parseTumTrajectory("1.0,0,0,0,0,0,0,1\n", "commas.txt").size(), 1u);
  EXPECT_THROW(readTumTrajectory("/nonexistent/traj.txt"), TrajectoryError);
}

}  // namespace
}  // namespace bmp

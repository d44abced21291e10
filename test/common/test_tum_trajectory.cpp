#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "bmp/common/number_format.hpp"
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

// A position of any size is written whole and reads back as itself (a fixed buffer cut a 1e300 line short,
// and the file could not be read again).
TEST(TumTrajectory, AHugePositionIsWrittenWhole) {
  Trajectory t{{1000.5, makeSE3({1e300, -2.5, 1e20}, Eigen::Quaterniond::Identity())}};
  const auto path = test::scratchDir("tum_traj_huge") / "t.txt";
  writeTumTrajectory(path.string(), t);
  const Trajectory r = readTumTrajectory(path.string());
  ASSERT_EQ(r.size(), 1u);
  EXPECT_DOUBLE_EQ(r[0].T_world_cam.translation().x(), 1e300);
  EXPECT_DOUBLE_EQ(r[0].T_world_cam.translation().z(), 1e20);
  EXPECT_EQ(formatFixed(1e100, 3, "n/a").size(), 105u);  // 101 digits, the point, 3 decimals
  EXPECT_EQ(formatFixed(-2.5, 1, "n/a"), "-2.5");
}

// Each appended pose is on disk at once (a killed writer leaves them all), and a final write replaces the
// live file whole.
TEST(TumTrajectory, StreamIsReadableAfterEachPoseAndFinalWriteReplacesIt) {
  const auto path = (test::scratchDir("tum_stream") / "live.txt").string();
  TumTrajectoryStream live(path, "live poses");
  for (int i = 0; i < 3; ++i) {
    live.append({10.0 + i, makeSE3({double(i), 0, 0}, Eigen::Quaterniond::Identity())});
    const Trajectory now = readTumTrajectory(path);  // while the stream is still open
    ASSERT_EQ(now.size(), static_cast<std::size_t>(i + 1));
    EXPECT_NEAR(now.back().T_world_cam.translation().x(), i, 1e-9);
  }
  EXPECT_EQ(test::readFirstLine(path), "# live poses");
  writeTumTrajectory(path, {{20.0, SE3::Identity()}});
  const Trajectory final_poses = readTumTrajectory(path);
  ASSERT_EQ(final_poses.size(), 1u);
  EXPECT_EQ(final_poses[0].stamp, 20.0);
}

// A restarted writer does not wipe what a killed one left: the old file becomes <path>.prev.
TEST(TumTrajectory, StreamKeepsAnEarlierFileAsPrev) {
  const auto dir = test::scratchDir("tum_stream_prev");
  const std::string path = (dir / "t.txt").string();
  {
    TumTrajectoryStream first(path, "");
    first.append({1.0, SE3::Identity()});
    first.append({2.0, SE3::Identity()});
    EXPECT_TRUE(first.previous().empty());
  }
  TumTrajectoryStream second(path, "");
  EXPECT_EQ(second.previous(), path + ".prev");
  EXPECT_EQ(readTumTrajectory(path + ".prev").size(), 2u);
  EXPECT_TRUE(readTumTrajectory(path).empty());
}

// A restart drops the poses written so far (a dropped map's) and leaves the kept previous file alone.
TEST(TumTrajectory, RestartDropsThePosesSoFarAndKeepsThePreviousFile) {
  const auto dir = test::scratchDir("tum_stream_restart");
  const std::string path = (dir / "t.txt").string();
  writeTumTrajectory(path, {{1.0, SE3::Identity()}});  // an earlier run's
  TumTrajectoryStream live(path, "live poses");
  live.append({5.0, SE3::Identity()});
  live.restart();
  EXPECT_TRUE(readTumTrajectory(path).empty());
  live.append({6.0, makeSE3({1.0, 0, 0}, Eigen::Quaterniond::Identity())});
  const Trajectory now = readTumTrajectory(path);
  ASSERT_EQ(now.size(), 1u);
  EXPECT_EQ(now[0].stamp, 6.0);
  EXPECT_EQ(test::readFirstLine(path), "# live poses");
  ASSERT_EQ(live.previous(), path + ".prev");
  const Trajectory earlier = readTumTrajectory(live.previous());
  ASSERT_EQ(earlier.size(), 1u);
  EXPECT_EQ(earlier[0].stamp, 1.0);
}

// The final write leaves no temporary behind and a file others can read.
TEST(TumTrajectory, FinalWriteLeavesOnlyTheFile) {
  const auto dir = test::scratchDir("tum_final");
  const std::string path = (dir / "t.txt").string();
  writeTumTrajectory(path, {{1.0, SE3::Identity()}});
  writeTumTrajectory(path, {{1.0, SE3::Identity()}, {2.0, SE3::Identity()}});
  EXPECT_EQ(readTumTrajectory(path).size(), 2u);
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    ++files;
    EXPECT_EQ(entry.path().filename(), "t.txt");
  }
  EXPECT_EQ(files, 1);
  const auto perms = std::filesystem::status(path).permissions();
  EXPECT_NE(perms & std::filesystem::perms::others_read, std::filesystem::perms::none);
}

TEST(TumTrajectory, UnwritablePathsAreErrorsNamingThem) {
  EXPECT_THROW(writeTumTrajectory("/nonexistent-dir/t.txt", {}), TrajectoryError);
  try {
    TumTrajectoryStream s("/nonexistent-dir/live.txt", "");
    FAIL();
  } catch (const TrajectoryError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent-dir/live.txt"), std::string::npos) << e.what();
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

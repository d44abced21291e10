// The floor fit: the lowest level plane with enough points, not the largest one, found from a poor guess
// of up; nothing when there is no floor.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "mapper/floor_plane.hpp"

namespace bmp::mapper {
namespace {

// A square patch of the plane z = height (in a frame tilted by tilt_deg about x), points every step metres.
void addPatch(PointList& cloud, double half, double height, double step, double tilt_deg = 0.0) {
  const double t = tilt_deg * M_PI / 180.0;
  for (double x = -half; x <= half; x += step)
    for (double y = -half; y <= half; y += step) {
      const Eigen::Vector3d p(x, std::cos(t) * y - std::sin(t) * height,
                              std::sin(t) * y + std::cos(t) * height);
      cloud.push_back(
          {static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z()), 0, 0, 0});
    }
}

void addWall(PointList& cloud, double x, double step) {
  for (double y = -2; y <= 2; y += step)
    for (double z = 0; z <= 2.5; z += step) cloud.push_back({float(x), float(y), float(z), 0, 0, 0});
}

TEST(FloorFit, TheLowestLevelPlaneNotTheLargest) {
  PointList cloud;
  addPatch(cloud, 2.0, 0.0, 0.05);   // the floor, partly seen
  addPatch(cloud, 1.0, 0.75, 0.02);  // a table top with more points than the floor
  addWall(cloud, 2.0, 0.03);         // a wall with the most points
  const auto floor = fitFloor(cloud, {0, 0.3, 1}, FloorSettings{});  // up guessed 17 degrees off
  ASSERT_TRUE(floor.has_value());
  EXPECT_GT(floor->normal.z(), std::cos(0.5 * M_PI / 180.0));
  EXPECT_NEAR(floor->height, 0.0, 0.01);
}

TEST(FloorFit, ATiltedWorldGetsItsFloorsNormal) {
  PointList cloud;
  addPatch(cloud, 2.0, -1.2, 0.04, 25.0);  // the first camera looked 25 degrees down, 1.2 m above the floor
  const auto floor = fitFloor(cloud, {0, 0, 1}, FloorSettings{});
  ASSERT_TRUE(floor.has_value());
  const Eigen::Vector3d expected(0, -std::sin(25 * M_PI / 180), std::cos(25 * M_PI / 180));
  EXPECT_GT(floor->normal.dot(expected), std::cos(0.5 * M_PI / 180.0));
  EXPECT_NEAR(floor->height, -1.2, 0.01);
  GridSettings grid;
  grid.floor.mode = FloorMode::kFit;
  const GridSettings grounded = groundedGrid(grid, floor);
  EXPECT_NEAR(grounded.height_min_m, -1.2 + grid.height_min_m, 0.01);
  EXPECT_NEAR(grounded.up[1], expected.y(), 0.01);
  EXPECT_EQ(grounded.axes_from, grid.up);  // the grid's axes are chosen by the configured up, not the fit
}

// A real room's cloud: the floor is a sixth of it, with depth noise near the support band (a structured-light
// camera's at 4-5 m), and the rest clutter over it. Three points drawn from the whole cloud lie on the floor
// in 0.5 % of samples, and least squares on the band of a plane a degree off keeps it off: on Bonn the fit
// was 1.5-13 degrees off, and the grid black where the floor is.
TEST(FloorFit, AFloorASixthOfACloudOfClutter) {
  const double tilt = 15.0 * M_PI / 180.0;                        // the first camera looked down
  const Eigen::Vector3d up(0, -std::cos(tilt), -std::sin(tilt));  // world: camera frame, y down
  const Eigen::Vector3d e1 = Eigen::Vector3d::UnitX(), e2 = up.cross(e1);
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0.0, 0.025);
  std::uniform_real_distribution<double> across(-3.0, 3.0), above(0.05, 2.2);
  PointList cloud;
  const auto add = [&](const Eigen::Vector3d& p) {
    cloud.push_back({float(p.x()), float(p.y()), float(p.z()), 0, 0, 0});
  };
  const double floor_height = -1.4;  // along up
  for (int i = 0; i < 4000; ++i) add(across(rng) * e1 + across(rng) * e2 + (floor_height + noise(rng)) * up);
  for (int i = 0; i < 20000; ++i) add(across(rng) * e1 + across(rng) * e2 + (floor_height + above(rng)) * up);
  const auto floor = fitFloor(cloud, {0, -1, 0}, FloorSettings{});
  ASSERT_TRUE(floor.has_value());
  EXPECT_GT(floor->normal.dot(up), std::cos(0.2 * M_PI / 180.0))
      << "normal " << floor->normal.transpose() << ", off by "
      << std::acos(std::min(1.0, floor->normal.dot(up))) * 180 / M_PI << " degrees";
  EXPECT_NEAR(floor->height, floor_height, 0.01);
}

TEST(FloorFit, NoFloorInViewFallsBackToTheConfiguredOne) {
  PointList cloud;
  addWall(cloud, 2.0, 0.03);
  FloorSettings s;
  EXPECT_FALSE(fitFloor(cloud, {0, 0, 1}, s).has_value());
  GridSettings grid;
  grid.up = {0, 0, 1};
  const GridSettings grounded = groundedGrid(grid, std::nullopt);
  EXPECT_NEAR(grounded.height_min_m, grid.floor.height_m + grid.height_min_m, 1e-12);
  EXPECT_EQ(grounded.up, grid.up);
}

}  // namespace
}  // namespace bmp::mapper

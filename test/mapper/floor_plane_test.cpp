// The floor fit: the lowest level plane with enough points, not the largest one, found from a poor guess
// of up; nothing when there is no floor.
#include <gtest/gtest.h>

#include <cmath>

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

#pragma once
// The 2-D occupancy grid planners use, and the frame of its floor plane in the world.
#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "bmp/common/se3.hpp"

namespace bmp::mapper {

inline constexpr int8_t kCellUnknown = -1;
inline constexpr int8_t kCellFree = 0;
inline constexpr int8_t kCellOccupied = 100;

// The floor plane's axes in the world: `up` is the floor's normal (or the configured up); x_axis is the world
// axis least aligned with `axes_from` (the configured up), made perpendicular to up; y_axis = up x x_axis, so
// (x_axis, y_axis, up) is right-handed. For up = +z the plane's axes are world x and y; for up = -y (the
// tracker's first camera) they are world x and world z (forward). The axis is chosen by the configured up,
// not the fitted normal: a camera pitched and rolled alike has a normal with two near-equal small components,
// and a refit that swapped them would turn the grid by 90 degrees under a planner.
struct PlaneFrame {
  Eigen::Vector3d x_axis = Eigen::Vector3d::UnitX();
  Eigen::Vector3d y_axis = Eigen::Vector3d::UnitY();
  Eigen::Vector3d up = Eigen::Vector3d::UnitZ();

  static PlaneFrame fromUp(const std::array<double, 3>& up) { return fromUp(up, up); }
  static PlaneFrame fromUp(const std::array<double, 3>& up, const std::array<double, 3>& axes_from);
  Eigen::Vector2d planar(const Eigen::Vector3d& p_world) const {
    return {x_axis.dot(p_world), y_axis.dot(p_world)};
  }
  double height(const Eigen::Vector3d& p_world) const { return up.dot(p_world); }
  // Rotation whose columns are the plane's axes: maps plane coordinates (x, y, height) into the world.
  Eigen::Matrix3d R_world_plane() const;
};

struct OccupancyGrid2D {
  double resolution = 0.05;                          // metres per cell
  int width = 0;                                     // cells along the plane's x
  int height = 0;                                    // cells along the plane's y
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();  // plane coordinates of cell (0, 0)'s outer corner
  PlaneFrame frame;
  std::vector<int8_t> cells;  // row-major (row = y index): kCellUnknown, kCellFree or kCellOccupied

  int8_t at(int col, int row) const { return cells[static_cast<std::size_t>(row) * width + col]; }
  // The cell holding a point of the plane, or false outside the grid.
  bool cellOf(const Eigen::Vector2d& planar, int& col, int& row) const;
  // Pose of cell (0, 0)'s corner in the world (the plane's axes as its rotation).
  SE3 T_world_origin() const;
};

}  // namespace bmp::mapper

#include "mapper/occupancy_grid.hpp"

#include <cmath>

namespace bmp::mapper {

PlaneFrame PlaneFrame::fromUp(const std::array<double, 3>& up_in, const std::array<double, 3>& axes_from) {
  PlaneFrame f;
  f.up = Eigen::Vector3d(up_in[0], up_in[1], up_in[2]).normalized();
  const Eigen::Vector3d from(axes_from[0], axes_from[1], axes_from[2]);
  int least = 0;
  (from.isZero() ? f.up : from).cwiseAbs().minCoeff(&least);
  // The first least-aligned axis: world x whenever the configured up is perpendicular to it, so the grid
  // reads like the world.
  const Eigen::Vector3d axis = Eigen::Vector3d::Unit(least);
  f.x_axis = (axis - axis.dot(f.up) * f.up).normalized();
  f.y_axis = f.up.cross(f.x_axis);
  return f;
}

Eigen::Matrix3d PlaneFrame::R_world_plane() const {
  Eigen::Matrix3d R;
  R.col(0) = x_axis;
  R.col(1) = y_axis;
  R.col(2) = up;
  return R;
}

bool OccupancyGrid2D::cellOf(const Eigen::Vector2d& planar, int& col, int& row) const {
  const Eigen::Vector2d rel = (planar - origin) / resolution;
  if (!rel.allFinite()) return false;
  col = static_cast<int>(std::floor(rel.x()));
  row = static_cast<int>(std::floor(rel.y()));
  return col >= 0 && row >= 0 && col < width && row < height;
}

SE3 OccupancyGrid2D::T_world_origin() const {
  SE3 T = SE3::Identity();
  T.linear() = frame.R_world_plane();
  T.translation() = frame.x_axis * origin.x() + frame.y_axis * origin.y();
  return T;
}

}  // namespace bmp::mapper

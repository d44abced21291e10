#pragma once
// The floor under the map: a plane fitted in the cloud (RANSAC, then least squares on its support), and
// the grid settings measured from it.
#include <optional>

#include <Eigen/Core>

#include "mapper/mapper_settings.hpp"
#include "mapper/point_types.hpp"

namespace bmp::mapper {

struct FloorPlane {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // unit, on the side of the configured up
  double height = 0.0;                                // normal . p for points p on the floor
  double share = 0.0;                                 // of the fitted points that support it
};

// The lowest plane within s.max_tilt_deg of up that at least s.min_share of the cloud supports; nullopt
// when there is none (too few points, a view with no floor). Deterministic for a given cloud.
std::optional<FloorPlane> fitFloor(const PointList& cloud, const Eigen::Vector3d& up, const FloorSettings& s);

// The grid settings with up and the height band in the world: along the floor's normal, from its height
// (grid heights are above the floor). Without a floor: the configured up and floor.height_m.
GridSettings groundedGrid(const GridSettings& grid, const std::optional<FloorPlane>& floor);

}  // namespace bmp::mapper

#pragma once
// The 2-D grid in the ROS map_server convention: a PGM image (row 0 is the grid's top, the largest y) and a
// YAML file with image, resolution, origin [x, y, yaw], negate, occupied_thresh, free_thresh. Coordinates are
// those of the grid's floor plane (PlaneFrame): with up = +z they are world x and y.
#include <string>

#include "mapper/occupancy_grid.hpp"

namespace bmp::mapper {

// map_server's trinary levels with negate 0: occupied black, free white, unknown grey.
inline constexpr int kPgmOccupied = 0;
inline constexpr int kPgmFree = 254;
inline constexpr int kPgmUnknown = 205;

std::string encodePgm(const OccupancyGrid2D& grid);
// image_name: the PGM's file name, relative to the YAML's folder.
std::string encodeMapYaml(const OccupancyGrid2D& grid, const std::string& image_name);

}  // namespace bmp::mapper

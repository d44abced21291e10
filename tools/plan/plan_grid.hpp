#pragma once
// A 2-D occupancy grid as a planner sees it: the mapper's grid, read from its map_server files or from the
// live OCCUPANCY_GRID. Coordinates are metres in the grid's floor plane (world x and y when the map's up is
// +z; see config/mapper.yaml for the tracker's frame).
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace bmp::plan {

inline constexpr int8_t kUnknown = -1;
inline constexpr int8_t kFree = 0;
inline constexpr int8_t kOccupied = 100;

struct PlanGrid {
  double resolution = 0.05;                          // metres per cell
  int width = 0, height = 0;                         // cells
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();  // plane coordinates of cell (0, 0)'s outer corner
  std::vector<int8_t> cells;                         // row-major, row = y index; -1, 0..100

  int8_t at(int col, int row) const { return cells[static_cast<std::size_t>(row) * width + col]; }
  bool inside(int col, int row) const { return col >= 0 && row >= 0 && col < width && row < height; }
  Eigen::Vector2i cellOf(const Eigen::Vector2d& p) const;
  Eigen::Vector2d centreOf(int col, int row) const;
};

class MapFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A ROS map_server map (YAML: image, resolution, origin, negate, occupied_thresh, free_thresh; the image
// read with OpenCV, its top row the grid's last). Cells whose occupancy probability exceeds
// occupied_thresh are occupied, those below free_thresh free, the others unknown. Throws MapFileError.
PlanGrid readMapServerMap(const std::string& yaml_path);

}  // namespace bmp::plan

#include "mapper/grid_files.hpp"

#include <cstdio>

#include "bmp/common/log.hpp"

namespace bmp::mapper {

namespace {
std::string vec(const Eigen::Vector3d& v) {
  return log::concat("[", v.x(), ", ", v.y(), ", ", v.z(), "]");
}
}  // namespace

std::string encodePgm(const OccupancyGrid2D& grid) {
  std::string out = "P5\n# bmp-mapper occupancy grid\n" + std::to_string(grid.width) + " " +
                    std::to_string(grid.height) + "\n255\n";
  const std::size_t start = out.size();
  out.resize(start + static_cast<std::size_t>(grid.width) * grid.height);
  for (int row = 0; row < grid.height; ++row) {
    char* line = &out[start + static_cast<std::size_t>(grid.height - 1 - row) * grid.width];
    for (int col = 0; col < grid.width; ++col) {
      const int8_t c = grid.at(col, row);
      line[col] = static_cast<char>(c == kCellOccupied ? kPgmOccupied
                                    : c == kCellFree   ? kPgmFree
                                                       : kPgmUnknown);
    }
  }
  return out;
}

std::string encodeMapYaml(const OccupancyGrid2D& grid, const std::string& image_name) {
  char numbers[160];
  std::snprintf(numbers, sizeof(numbers), "resolution: %.6f\norigin: [%.6f, %.6f, 0.0]\n", grid.resolution,
                grid.origin.x(), grid.origin.y());
  // The plane's axes as keys a program can read (map_server reads only its own): a pose from SLAM_POSE is
  // in the world frame, and the grid's floor plane is the fitted one, not the world's.
  return "# bmp-mapper occupancy grid, ROS map_server convention.\nimage: " + image_name + "\n" + numbers +
         "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n"
         "# The grid's plane in the world frame (the tracker's first camera): a world point p is at plane\n"
         "# coordinates (plane_x_axis . p, plane_y_axis . p), which origin and resolution turn into a cell;\n"
         "# plane_up is the axis the grid is projected along (the fitted floor's normal). The floor may be\n"
         "# fitted again as the map grows: read these with each grid.\n"
         "plane_x_axis: " +
         vec(grid.frame.x_axis) + "\nplane_y_axis: " + vec(grid.frame.y_axis) +
         "\nplane_up: " + vec(grid.frame.up) + "\n";
}

}  // namespace bmp::mapper

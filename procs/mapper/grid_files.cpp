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
  return "# bmp-mapper occupancy grid, ROS map_server convention.\n"
         "# Its plane's axes in the world frame (x, y, and the up axis the grid is projected along):\n"
         "#   x_axis " +
         vec(grid.frame.x_axis) + "\n#   y_axis " + vec(grid.frame.y_axis) + "\n#   up " +
         vec(grid.frame.up) + "\nimage: " + image_name + "\n" + numbers +
         "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n";
}

}  // namespace bmp::mapper

#pragma once
// Shortest collision-free path on the grid: A* over 8-connected cells, after occupied cells are grown by
// the robot's radius.
#include <string>
#include <vector>

#include "plan/plan_grid.hpp"

namespace bmp::plan {

struct PlanOptions {
  double robot_radius_m = 0.2;     // occupied cells block every cell whose centre lies this close
  bool unknown_is_blocked = true;  // unknown cells are not driven through (they are not grown)
};

struct PlanResult {
  bool found = false;
  std::string reason;                   // why no path ("" when found)
  std::vector<Eigen::Vector2i> cells;   // start to goal
  std::vector<Eigen::Vector2d> points;  // cell centres, plane metres
  double length_m = 0.0;
};

// Cells the robot's centre must not enter: 1 blocked, 0 free to drive.
std::vector<uint8_t> blockedCells(const PlanGrid& grid, const PlanOptions& options);

// Diagonal steps may not cut a blocked corner. Start and goal must lie in the grid on cells not blocked.
PlanResult planPath(const PlanGrid& grid, const Eigen::Vector2d& from, const Eigen::Vector2d& to,
                    const PlanOptions& options);

}  // namespace bmp::plan

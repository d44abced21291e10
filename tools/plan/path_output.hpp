#pragma once
// A planned path as a picture over the grid and as text.
#include <string>

#include <opencv2/core.hpp>

#include "plan/astar.hpp"

namespace bmp::plan {

// The grid (free white, occupied black, unknown grey, cells the robot radius blocks light red), the path
// in blue, start green, goal red; cell_px pixels per cell, the plane's y upwards.
cv::Mat drawPath(const PlanGrid& grid, const PlanResult& path, const PlanOptions& options, int cell_px);
// "# x y (metres, grid plane)" then one "x y" line per path point; a comment line when no path.
std::string pathText(const PlanResult& path);

}  // namespace bmp::plan

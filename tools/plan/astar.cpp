#include "plan/astar.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>

#include <opencv2/imgproc.hpp>

namespace bmp::plan {

namespace {

struct Open {
  double f;
  int index;
  bool operator>(const Open& o) const { return f > o.f; }
};

double octile(const Eigen::Vector2i& a, const Eigen::Vector2i& b) {
  const int dx = std::abs(a.x() - b.x()), dy = std::abs(a.y() - b.y());
  return std::max(dx, dy) + (std::sqrt(2.0) - 1.0) * std::min(dx, dy);
}

std::string refuseEnd(const PlanGrid& grid, const std::vector<uint8_t>& blocked, const Eigen::Vector2i& c,
                      const char* what) {
  if (!grid.inside(c.x(), c.y())) return std::string(what) + " lies outside the grid";
  if (blocked[static_cast<std::size_t>(c.y()) * grid.width + c.x()] != 0)
    return std::string(what) + " is blocked (occupied, unknown, or within the robot radius of an obstacle)";
  return "";
}

// Walks the parents back from goal and measures the path.
void tracePath(const PlanGrid& grid, const std::vector<int>& parent, int goal, PlanResult& r) {
  for (int i = goal; i >= 0; i = parent[i]) r.cells.emplace_back(i % grid.width, i / grid.width);
  std::reverse(r.cells.begin(), r.cells.end());
  for (std::size_t k = 0; k < r.cells.size(); ++k) {
    r.points.push_back(grid.centreOf(r.cells[k].x(), r.cells[k].y()));
    if (k > 0) r.length_m += (r.points[k] - r.points[k - 1]).norm();
  }
  r.found = true;
}

}  // namespace

std::vector<uint8_t> blockedCells(const PlanGrid& grid, const PlanOptions& options) {
  const std::size_t n = grid.cells.size();
  std::vector<uint8_t> blocked(n, 0);
  if (n == 0) return blocked;
  // Distance from every cell to the nearest occupied one, in cells: 0 marks the obstacles themselves.
  cv::Mat free_space(grid.height, grid.width, CV_8U);
  for (std::size_t i = 0; i < n; ++i) free_space.data[i] = grid.cells[i] >= 50 ? 0 : 255;
  cv::Mat distance;
  cv::distanceTransform(free_space, distance, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  const float reach = static_cast<float>(options.robot_radius_m / grid.resolution);
  for (std::size_t i = 0; i < n; ++i) {
    const bool near = reinterpret_cast<const float*>(distance.data)[i] <= reach;
    const bool unknown = grid.cells[i] < 0 && options.unknown_is_blocked;
    blocked[i] = near || unknown ? 1 : 0;
  }
  return blocked;
}

PlanResult planPath(const PlanGrid& grid, const Eigen::Vector2d& from, const Eigen::Vector2d& to,
                    const PlanOptions& options) {
  PlanResult r;
  const std::vector<uint8_t> blocked = blockedCells(grid, options);
  const Eigen::Vector2i start = grid.cellOf(from), goal = grid.cellOf(to);
  r.reason = refuseEnd(grid, blocked, start, "start");
  if (r.reason.empty()) r.reason = refuseEnd(grid, blocked, goal, "goal");
  if (!r.reason.empty()) return r;

  const int w = grid.width;
  std::vector<double> cost(grid.cells.size(), std::numeric_limits<double>::infinity());
  std::vector<int> parent(grid.cells.size(), -1);
  std::priority_queue<Open, std::vector<Open>, std::greater<>> open;
  const int start_index = start.y() * w + start.x(), goal_index = goal.y() * w + goal.x();
  cost[start_index] = 0;
  open.push({octile(start, goal), start_index});
  const auto free_at = [&](int col, int row) { return grid.inside(col, row) && blocked[row * w + col] == 0; };
  while (!open.empty()) {
    const Open top = open.top();
    open.pop();
    if (top.index == goal_index) {
      tracePath(grid, parent, goal_index, r);
      return r;
    }
    const Eigen::Vector2i c(top.index % w, top.index / w);
    if (top.f - octile(c, goal) > cost[top.index] + 1e-9) continue;  // a stale entry
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        if ((dx == 0 && dy == 0) || !free_at(c.x() + dx, c.y() + dy)) continue;
        if (dx != 0 && dy != 0 && (!free_at(c.x() + dx, c.y()) || !free_at(c.x(), c.y() + dy))) continue;
        const int next = (c.y() + dy) * w + c.x() + dx;
        const double g = cost[top.index] + (dx != 0 && dy != 0 ? std::sqrt(2.0) : 1.0);
        if (g >= cost[next]) continue;
        cost[next] = g;
        parent[next] = top.index;
        open.push({g + octile({c.x() + dx, c.y() + dy}, goal), next});
      }
    }
  }
  r.reason = "no collision-free path: the goal cannot be reached from the start";
  return r;
}

}  // namespace bmp::plan

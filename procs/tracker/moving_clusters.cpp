#include "tracker/moving_clusters.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "tracker/keypoint_window_grid.hpp"

namespace bmp::tracker {

std::vector<MovingCluster> movingClusters(const Features& f, const FrameGeometry& g,
                                          const std::vector<int8_t>& verdict, double link_px,
                                          double link_depth_m, int min_size) {
  // Union-find over the keypoints that moved; neighbours come from a grid of them alone, so the cost stays
  // near linear however many moved.
  std::vector<int> parent(static_cast<std::size_t>(f.size()));
  std::iota(parent.begin(), parent.end(), 0);
  const auto root = [&parent](int a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  };
  const auto usable = [&](int i) { return verdict[i] == 1 && f.depth[i] > 0; };
  const double link2 = link_px * link_px;
  // Any keypoint that moved searches, but only those in the frame's grid (not excluded, inside its bounds)
  // can be found; packed, a search reads no keypoint that did not move.
  const auto grid =
      KeypointWindowGrid::ofFrameGrid(f, g, link_px, [&](int j) { return link_px > 0 && usable(j); });
  for (int i = 0; i < f.size(); ++i) {
    if (!usable(i) || grid.empty()) continue;
    grid.forEach(f.un[i].x(), f.un[i].y(), link_px, -1, -1, [&](int j) {
      if (j <= i || (f.un[i] - f.un[j]).squaredNorm() > link2 ||
          std::abs(f.depth[i] - f.depth[j]) > link_depth_m)
        return;
      parent[root(j)] = root(i);
    });
  }
  std::vector<int> slot(static_cast<std::size_t>(f.size()), -1);
  std::vector<MovingCluster> all;
  for (int i = 0; i < f.size(); ++i) {
    if (!usable(i)) continue;
    int& s = slot[root(i)];
    const double u = f.un[i].x(), v = f.un[i].y(), d = f.depth[i];
    if (s < 0) {
      s = static_cast<int>(all.size());
      all.push_back({0, u, v, u, v, d, d});
    }
    MovingCluster& c = all[s];
    ++c.size;
    c.u0 = std::min(c.u0, u), c.u1 = std::max(c.u1, u);
    c.v0 = std::min(c.v0, v), c.v1 = std::max(c.v1, v);
    c.near_m = std::min(c.near_m, d), c.far_m = std::max(c.far_m, d);
  }
  const auto rejected = [&](const MovingCluster& c) {
    if (c.size < min_size) return true;
    int stayed = 0;
    for (int i = 0; i < f.size(); ++i)
      stayed += verdict[i] == 0 && f.depth[i] > 0 && c.covers(f.un[i].x(), f.un[i].y(), f.depth[i], 0.0);
    return stayed > c.size;
  };
  all.erase(std::remove_if(all.begin(), all.end(), rejected), all.end());
  return all;
}

}  // namespace bmp::tracker

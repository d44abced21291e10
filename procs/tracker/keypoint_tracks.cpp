#include "tracker/keypoint_tracks.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "tracker/matcher.hpp"

namespace bmp::tracker {

namespace {

// The frame's keypoints bucketed in cells as wide as the search window, packed: a window then spans at most
// 3 x 3 cells, where the frame's fine grid (kGridCols x kGridRows) would need 9 x 9 at 40 px. The order in
// which candidates come does not change the result: a tie for the closest fails the ratio test.
class WindowGrid {
 public:
  WindowGrid(const Features& f, const FrameGeometry& g, double radius) : g_(g), cell_(std::max(1.0, radius)) {
    cols_ = std::max(1, static_cast<int>(std::ceil((g.max_x - g.min_x) / cell_)));
    rows_ = std::max(1, static_cast<int>(std::ceil((g.max_y - g.min_y) / cell_)));
    start_.assign(static_cast<std::size_t>(cols_) * rows_ + 1, 0);
    std::vector<int> cell_of(static_cast<std::size_t>(f.size()));
    for (int i = 0; i < f.size(); ++i) {
      cell_of[i] = cellIndex(f.un[i].x(), f.un[i].y());
      ++start_[cell_of[i] + 1];
    }
    for (std::size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
    entries_.resize(static_cast<std::size_t>(f.size()));
    std::vector<int> fill(start_.begin(), start_.end() - 1);
    for (int i = 0; i < f.size(); ++i)
      entries_[fill[cell_of[i]]++] = {f.un[i].x(), f.un[i].y(), f.level(i), i};
  }

  // Calls fn(i) for each keypoint within r of (u, v) on levels [lo, hi].
  template <class Fn>
  void forEach(double u, double v, double r, int lo, int hi, Fn&& fn) const {
    const int c0 = column(u - r), c1 = column(u + r), r0 = row(v - r), r1 = row(v + r);
    for (int row = r0; row <= r1; ++row)
      for (int col = c0; col <= c1; ++col) {
        const int c = row * cols_ + col;
        for (int k = start_[c]; k < start_[c + 1]; ++k) {
          const Entry& e = entries_[k];
          if (e.level < lo || e.level > hi) continue;
          if (std::abs(e.u - u) < r && std::abs(e.v - v) < r) fn(e.index);
        }
      }
  }

 private:
  struct Entry {
    double u, v;
    int level, index;
  };
  int column(double u) const {
    return std::clamp(static_cast<int>(std::floor((u - g_.min_x) / cell_)), 0, cols_ - 1);
  }
  int row(double v) const {
    return std::clamp(static_cast<int>(std::floor((v - g_.min_y) / cell_)), 0, rows_ - 1);
  }
  int cellIndex(double u, double v) const { return row(v) * cols_ + column(u); }

  const FrameGeometry& g_;
  double cell_;
  int cols_ = 1, rows_ = 1;
  std::vector<int> start_;  // per cell, its first entry; one past the end last
  std::vector<Entry> entries_;
};

}  // namespace

std::vector<int> trackFromLastFrame(const Frame& frame, const Frame& last, const FrameGeometry& g,
                                    const std::vector<uint8_t>& open, const KeypointTrackOptions& options) {
  const Features& cur = *frame.features;
  const Features& prev = *last.features;
  std::vector<int> track(static_cast<std::size_t>(cur.size()), -1);
  std::vector<int> best_distance(static_cast<std::size_t>(cur.size()), std::numeric_limits<int>::max());
  const SE3 T_cur_last = frame.T_cam_world() * last.T_world_cam();
  const WindowGrid window(cur, g, options.radius_px);
  for (int j = 0; j < prev.size(); ++j) {
    if (!prev.hasDepth(j) || prev.excluded[j]) continue;
    const Eigen::Vector3d p = T_cur_last * g.camera.backProject(prev.un[j], prev.depth[j]);
    if (p.z() <= 0.0) continue;
    const Eigen::Vector2d q = g.project(p);
    if (!g.inBounds(q.x(), q.y())) continue;
    const int level = prev.level(j);
    ClosestTwo c;
    window.forEach(q.x(), q.y(), options.radius_px, level - 1, level + 1,
                   [&](int i) { c.offer(i, hamming(prev.descriptor(j), cur.descriptor(i))); });
    // The best must be clearly the best: a wide window holds many look-alikes.
    if (c.best < 0 || c.best_dist > options.max_distance || c.best_dist >= options.ratio * c.second_dist)
      continue;
    if (!open[c.best] || c.best_dist >= best_distance[c.best]) continue;
    best_distance[c.best] = c.best_dist;
    track[c.best] = j;
  }
  return track;
}

}  // namespace bmp::tracker

#pragma once
// A frame's keypoints (or a chosen subset) bucketed for wide window searches: cells as wide as the search
// window, so a window spans at most 3 x 3 of them (the frame's fine grid would need 9 x 9 at 40 px), and
// each cell's keypoints sorted by pyramid level, so a search limited to a few levels reads only those. The
// entries are packed (position and index), so a search reads no keypoint it does not return.
// Callers must not depend on the order of the calls: it is by cell, then level, then index.
#include <cmath>
#include <vector>

#include "tracker/frame.hpp"

namespace bmp::tracker {

class KeypointWindowGrid {
 public:
  // Buckets keypoints `indices` of f in square cells `cell_px` wide (at least the frame grid's cells) over
  // the image bounds; a keypoint outside them goes to the nearest edge cell. Levels are ORB octaves (>= 0).
  KeypointWindowGrid(const Features& f, const FrameGeometry& g, double cell_px,
                     const std::vector<int>& indices);
  // The frame grid's keypoints (not excluded, inside the bounds) for which keep(i) holds.
  template <class Keep>
  static KeypointWindowGrid ofFrameGrid(const Features& f, const FrameGeometry& g, double cell_px,
                                        Keep&& keep) {
    std::vector<int> indices;
    for (const auto& cell : f.grid)
      for (int i : cell)
        if (keep(i)) indices.push_back(i);
    return KeypointWindowGrid(f, g, cell_px, indices);
  }
  bool empty() const { return entries_.empty(); }

  // Calls fn(i) for each bucketed keypoint with |u_i - u| < r and |v_i - v| < r (the fine grid's test) on
  // levels [lo, hi]; lo < 0 or hi < 0: no bound on that side.
  template <class Fn>
  void forEach(double u, double v, double r, int lo, int hi, Fn&& fn) const {
    if (!(std::isfinite(u) && std::isfinite(v) && r >= 0.0)) return;  // a projection gone wrong finds nothing
    lo = lo < 0 ? 0 : lo;
    hi = hi < 0 || hi >= levels_ ? levels_ - 1 : hi;
    if (lo > hi) return;
    const int c0 = column(u - r), c1 = column(u + r), r0 = row(v - r), r1 = row(v + r);
    for (int y = r0; y <= r1; ++y)
      for (int x = c0; x <= c1; ++x) {
        const std::size_t base = static_cast<std::size_t>(y * cols_ + x) * levels_;
        for (int k = start_[base + lo]; k < start_[base + hi + 1]; ++k) {
          const Entry& e = entries_[k];
          if (std::abs(e.u - u) < r && std::abs(e.v - v) < r) fn(e.index);
        }
      }
  }

 private:
  struct Entry {
    double u, v;
    int index;
  };
  int column(double u) const;
  int row(double v) const;

  double min_x_, min_y_, cell_;
  int cols_ = 1, rows_ = 1, levels_ = 1;
  std::vector<int> start_;  // per (cell, level), its first entry; one past the end last
  std::vector<Entry> entries_;
};

}  // namespace bmp::tracker

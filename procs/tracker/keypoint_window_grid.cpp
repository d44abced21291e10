#include "tracker/keypoint_window_grid.hpp"

#include <algorithm>
#include <cmath>

namespace bmp::tracker {

KeypointWindowGrid::KeypointWindowGrid(const Features& f, const FrameGeometry& g, double cell_px,
                                       const std::vector<int>& indices)
    // Cells no finer than the frame's grid: a tiny window (or none) must not cost an image-sized table.
    : min_x_(g.min_x), min_y_(g.min_y), cell_(std::max({g.grid_cell_w, g.grid_cell_h, 1.0, cell_px})) {
  cols_ = std::max(1, static_cast<int>(std::ceil((g.max_x - g.min_x) / cell_)));
  rows_ = std::max(1, static_cast<int>(std::ceil((g.max_y - g.min_y) / cell_)));
  for (int i : indices) levels_ = std::max(levels_, f.level(i) + 1);
  // A counting sort on (cell, level): stable, so each bucket keeps the order of `indices`.
  start_.assign(static_cast<std::size_t>(cols_) * rows_ * levels_ + 1, 0);
  std::vector<int> bucket_of(indices.size());
  for (std::size_t k = 0; k < indices.size(); ++k) {
    const int i = indices[k];
    bucket_of[k] = (row(f.un[i].y()) * cols_ + column(f.un[i].x())) * levels_ + std::max(0, f.level(i));
    ++start_[bucket_of[k] + 1];
  }
  for (std::size_t b = 1; b < start_.size(); ++b) start_[b] += start_[b - 1];
  entries_.resize(indices.size());
  std::vector<int> fill(start_.begin(), start_.end() - 1);
  for (std::size_t k = 0; k < indices.size(); ++k) {
    const int i = indices[k];
    entries_[fill[bucket_of[k]]++] = {f.un[i].x(), f.un[i].y(), i};
  }
}

int KeypointWindowGrid::column(double u) const {
  return clampedCell(std::floor((u - min_x_) / cell_), cols_);
}

int KeypointWindowGrid::row(double v) const {
  return clampedCell(std::floor((v - min_y_) / cell_), rows_);
}

}  // namespace bmp::tracker

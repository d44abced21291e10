#include "tracker/cell_corners.hpp"

#include <algorithm>

#include <opencv2/features2d.hpp>

namespace bmp::tracker {
namespace {
// FAST's circle has radius 3, and suppression compares with the 8 neighbours: a corner's verdict depends on
// pixels up to 4 away, so a cell run on the cell grown by 4 finds exactly what a whole-image run finds there.
constexpr int kReach = 4;
}  // namespace

std::vector<cv::KeyPoint> cellCorners(const cv::Mat& image, const CellCornerOptions& o) {
  const int w = image.cols, h = image.rows, cell = o.cell, b = o.border;
  const int cols = (w + cell - 1) / cell, rows = (h + cell - 1) / cell;
  // FAST's corners lie on whole pixels.
  const auto pixel = [](const cv::KeyPoint& kp) {
    return cv::Point(static_cast<int>(kp.pt.x), static_cast<int>(kp.pt.y));
  };
  const cv::Rect usable(b, b, w - 2 * b, h - 2 * b);
  std::vector<cv::KeyPoint> strong;
  cv::FAST(image, strong, std::max(o.threshold, o.min_threshold), true);
  std::vector<cv::KeyPoint> out;
  out.reserve(strong.size());
  std::vector<uint8_t> strong_cell(static_cast<std::size_t>(cols * rows), 0);
  for (const auto& kp : strong) {
    const cv::Point p = pixel(kp);
    if (!usable.contains(p)) continue;
    out.push_back(kp);
    strong_cell[p.y / cell * cols + p.x / cell] = 1;
  }
  if (o.min_threshold >= o.threshold) return out;
  const cv::Rect whole(0, 0, w, h);
  std::vector<cv::KeyPoint> weak;
  // One run per stretch of neighbouring weak cells in a cell row: each call has a fixed cost.
  for (int cy = 0; cy < rows; ++cy)
    for (int cx = 0; cx < cols;) {
      if (strong_cell[cy * cols + cx]) {
        ++cx;
        continue;
      }
      int end = cx + 1;
      while (end < cols && !strong_cell[cy * cols + end]) ++end;
      const cv::Rect area = cv::Rect(cx * cell, cy * cell, (end - cx) * cell, cell) & usable;
      cx = end;
      if (area.empty()) continue;
      const cv::Rect grown =
          cv::Rect(area.x - kReach, area.y - kReach, area.width + 2 * kReach, area.height + 2 * kReach) &
          whole;
      cv::FAST(image(grown), weak, o.min_threshold, true);
      for (auto kp : weak) {
        kp.pt.x += static_cast<float>(grown.x), kp.pt.y += static_cast<float>(grown.y);
        if (area.contains(pixel(kp))) out.push_back(kp);
      }
    }
  // FAST's own order, which ties in the later sort by response depend on.
  std::sort(out.begin(), out.end(), [](const cv::KeyPoint& a, const cv::KeyPoint& c) {
    return a.pt.y != c.pt.y ? a.pt.y < c.pt.y : a.pt.x < c.pt.x;
  });
  return out;
}

}  // namespace bmp::tracker

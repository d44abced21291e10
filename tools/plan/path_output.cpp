#include "plan/path_output.hpp"

#include <cstdio>

#include <opencv2/imgproc.hpp>

namespace bmp::plan {

cv::Mat drawPath(const PlanGrid& grid, const PlanResult& path, const PlanOptions& options, int cell_px) {
  const std::vector<uint8_t> blocked = blockedCells(grid, options);
  cv::Mat image(std::max(1, grid.height) * cell_px, std::max(1, grid.width) * cell_px, CV_8UC3);
  const auto pixel = [&](int col, int row) {
    return cv::Point(col * cell_px + cell_px / 2, (grid.height - 1 - row) * cell_px + cell_px / 2);
  };
  for (int row = 0; row < grid.height; ++row) {
    for (int col = 0; col < grid.width; ++col) {
      const int8_t c = grid.at(col, row);
      cv::Scalar colour = c >= 50 ? cv::Scalar(0, 0, 0)
                          : c < 0 ? cv::Scalar(128, 128, 128)
                                  : cv::Scalar(255, 255, 255);
      if (c >= 0 && c < 50 && blocked[static_cast<std::size_t>(row) * grid.width + col] != 0)
        colour = cv::Scalar(200, 200, 255);
      image(cv::Rect(col * cell_px, (grid.height - 1 - row) * cell_px, cell_px, cell_px)).setTo(colour);
    }
  }
  for (std::size_t k = 1; k < path.cells.size(); ++k)
    cv::line(image, pixel(path.cells[k - 1].x(), path.cells[k - 1].y()),
             pixel(path.cells[k].x(), path.cells[k].y()), cv::Scalar(255, 0, 0), std::max(1, cell_px / 2));
  if (!path.cells.empty()) {
    const int radius = std::max(2, cell_px);
    cv::circle(image, pixel(path.cells.front().x(), path.cells.front().y()), radius, cv::Scalar(0, 180, 0),
               -1);
    cv::circle(image, pixel(path.cells.back().x(), path.cells.back().y()), radius, cv::Scalar(0, 0, 255), -1);
  }
  return image;
}

std::string pathText(const PlanResult& path) {
  if (!path.found) return "# no path: " + path.reason + "\n";
  std::string out = "# x y (metres, grid plane); length " + std::to_string(path.length_m) + " m\n";
  char line[64];
  for (const auto& p : path.points) {
    std::snprintf(line, sizeof(line), "%.3f %.3f\n", p.x(), p.y());
    out += line;
  }
  return out;
}

}  // namespace bmp::plan

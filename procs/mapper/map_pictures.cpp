#include "mapper/map_pictures.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <opencv2/imgproc.hpp>

namespace bmp::mapper {

namespace {

const cv::Vec3b kBackground(40, 40, 40);

// An orthographic view: picture axes `right` and `down`, and `forward` as depth (smaller is nearer).
struct View {
  Eigen::Vector3d right, down, forward;
};

cv::Mat render(const PointList& cloud, const View& view, double max_height, const PlaneFrame& frame,
               int size_px) {
  std::vector<Eigen::Vector3d> projected;  // picture x, picture y, depth
  std::vector<cv::Vec3b> colours;
  Eigen::Vector2d lo(std::numeric_limits<double>::max(), std::numeric_limits<double>::max());
  Eigen::Vector2d hi = -lo;
  for (const auto& p : cloud) {
    const Eigen::Vector3d q(p.x, p.y, p.z);
    if (!q.allFinite() || frame.height(q) > max_height) continue;  // a point not a number has no pixel
    projected.emplace_back(view.right.dot(q), view.down.dot(q), view.forward.dot(q));
    colours.emplace_back(p.b, p.g, p.r);
    lo = lo.cwiseMin(projected.back().head<2>());
    hi = hi.cwiseMax(projected.back().head<2>());
  }
  if (projected.empty()) return cv::Mat(size_px / 2, size_px, CV_8UC3, cv::Scalar(40, 40, 40));
  const double margin = 8;
  const double extent = std::max({hi.x() - lo.x(), hi.y() - lo.y(), 1e-3});
  const double scale = (size_px - 2 * margin) / extent;
  const int width = static_cast<int>((hi.x() - lo.x()) * scale + 2 * margin) + 1;
  const int height = static_cast<int>((hi.y() - lo.y()) * scale + 2 * margin) + 1;
  cv::Mat image(height, width, CV_8UC3, kBackground);
  cv::Mat depth(height, width, CV_32F, cv::Scalar(std::numeric_limits<float>::max()));
  for (std::size_t i = 0; i < projected.size(); ++i) {
    const int u = static_cast<int>((projected[i].x() - lo.x()) * scale + margin);
    const int v = static_cast<int>((projected[i].y() - lo.y()) * scale + margin);
    const auto d = static_cast<float>(projected[i].z());
    // A 2x2 splat, so a sparse cloud still reads as surfaces.
    for (int dv = 0; dv < 2; ++dv) {
      for (int du = 0; du < 2; ++du) {
        const int x = std::min(u + du, width - 1), y = std::min(v + dv, height - 1);
        if (d < depth.at<float>(y, x)) {
          depth.at<float>(y, x) = d;
          image.at<cv::Vec3b>(y, x) = colours[i];
        }
      }
    }
  }
  return image;
}

}  // namespace

cv::Mat renderTopView(const PointList& cloud, const PlaneFrame& frame, const GridSettings& grid,
                      const PictureSettings& settings) {
  const View view{frame.x_axis, -frame.y_axis, -frame.up};
  return render(cloud, view, grid.height_max_m + settings.cut_above_m, frame, settings.size_px);
}

cv::Mat renderObliqueView(const PointList& cloud, const PlaneFrame& frame, const GridSettings& grid,
                          const PictureSettings& settings) {
  const double el = settings.oblique_elevation_deg * M_PI / 180.0;
  const double az = settings.oblique_azimuth_deg * M_PI / 180.0;
  const Eigen::Vector3d horizontal = std::cos(az) * frame.x_axis + std::sin(az) * frame.y_axis;
  // From where the viewer stands towards the scene: along -horizontal, and downwards.
  const Eigen::Vector3d forward = (-std::cos(el) * horizontal - std::sin(el) * frame.up).normalized();
  const Eigen::Vector3d right = forward.cross(frame.up).normalized();
  const Eigen::Vector3d down = forward.cross(right);
  return render(cloud, View{right, down, forward}, grid.height_max_m + settings.cut_above_m, frame,
                settings.size_px);
}

cv::Mat renderGrid(const OccupancyGrid2D& grid, int cell_px) {
  // One pixel a cell first (north up), then scaled to cell_px within the picture budget.
  const int w = std::max(1, grid.width), h = std::max(1, grid.height);
  cv::Mat cells(h, w, CV_8UC1, cv::Scalar(128));
  for (int row = 0; row < grid.height; ++row) {
    uchar* out = cells.ptr<uchar>(grid.height - 1 - row);
    for (int col = 0; col < grid.width; ++col) {
      const int8_t c = grid.at(col, row);
      out[col] = c == kCellOccupied ? 0 : c == kCellFree ? 255 : 128;
    }
  }
  const int side = std::max(w, h);
  cv::Mat scaled;
  if (side * cell_px <= kMaxGridPicturePx) {
    cv::resize(cells, scaled, cv::Size(w * cell_px, h * cell_px), 0, 0, cv::INTER_NEAREST);
  } else {  // cells under a pixel: each pixel the mean of its cells (grey where walls and free space mix)
    const double f = static_cast<double>(kMaxGridPicturePx) / side;
    cv::resize(cells, scaled,
               cv::Size(std::max(1, static_cast<int>(w * f)), std::max(1, static_cast<int>(h * f))), 0, 0,
               f < 1.0 ? cv::INTER_AREA : cv::INTER_NEAREST);
  }
  cv::Mat image;
  cv::cvtColor(scaled, image, cv::COLOR_GRAY2BGR);
  return image;
}

}  // namespace bmp::mapper

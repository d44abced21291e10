#include "tracker/frame.hpp"

#include <algorithm>
#include <cmath>

#include "tracker/map_point.hpp"

namespace bmp::tracker {

FrameGeometry::FrameGeometry(const CameraIntrinsics& k, const TrackerConfig& config)
    : camera(k),
      pyramid(config.orb.num_levels, config.orb.scale_factor),
      fx(k.fx),
      fy(k.fy),
      cx(k.cx),
      cy(k.cy),
      bf(k.fx * config.tracking.virtual_baseline_m),
      close_depth(config.tracking.close_depth_m),
      min_depth(config.tracking.min_depth_m),
      max_depth(config.tracking.max_depth_m) {
  // Undistorted image bounds from the corners, so the grid covers every keypoint.
  const Eigen::Vector2d tl = camera.undistortPixel({0, 0}), tr = camera.undistortPixel({k.width, 0});
  const Eigen::Vector2d bl = camera.undistortPixel({0, k.height}),
                        br = camera.undistortPixel({k.width, k.height});
  min_x = std::min(tl.x(), bl.x());
  max_x = std::max(tr.x(), br.x());
  min_y = std::min(tl.y(), tr.y());
  max_y = std::max(bl.y(), br.y());
  grid_cell_w = (max_x - min_x) / kGridCols;
  grid_cell_h = (max_y - min_y) / kGridRows;
}

int Features::numExcluded() const {
  return static_cast<int>(std::count(excluded.begin(), excluded.end(), 1));
}

std::vector<int> Features::nearestWithDepth() const {
  std::vector<int> order;
  for (int i = 0; i < size(); ++i)
    if (hasDepth(i) && !excluded[i]) order.push_back(i);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return depth[a] < depth[b]; });
  return order;
}

std::shared_ptr<const Features> buildFeatures(OrbFeatures orb, const cv::Mat& depth, const FrameGeometry& g,
                                              const KeypointWeightFn& weight_fn,
                                              const cv::Mat& exclusion_mask) {
  auto f = std::make_shared<Features>();
  f->keys = std::move(orb.keys);
  f->descriptors = orb.descriptors;
  const int n = f->size();
  f->un.resize(n);
  f->depth.assign(n, 0.0f);
  f->weight.assign(n, 1.0f);
  f->excluded.assign(n, 0);
  f->grid.assign(FrameGeometry::kGridCols * FrameGeometry::kGridRows, {});
  const double scale = g.camera.intrinsics().depth_scale;
  for (int i = 0; i < n; ++i) {
    const cv::Point2f& pt = f->keys[i].pt;
    f->un[i] = g.camera.undistortPixel({pt.x, pt.y});
    const int x = cvRound(pt.x), y = cvRound(pt.y);
    // Depth is registered to the raw (distorted) colour image, so it is read at the raw pixel.
    if (!depth.empty() && x >= 0 && y >= 0 && x < depth.cols && y < depth.rows) {
      const double d = depthMetresAt(depth, x, y, scale);
      if (std::isfinite(d) && d >= g.min_depth && d <= g.max_depth) f->depth[i] = static_cast<float>(d);
    }
    if (!exclusion_mask.empty() && x >= 0 && y >= 0 && x < exclusion_mask.cols && y < exclusion_mask.rows &&
        exclusion_mask.at<uint8_t>(y, x) != 0)
      f->excluded[i] = 1;
    if (weight_fn) {
      const float w = std::clamp(weight_fn(f->keys[i], f->depth[i]), 0.0f, 1.0f);
      f->weight[i] = w;
      if (w <= 0.0f) f->excluded[i] = 1;
    }
    if (f->excluded[i]) continue;
    // Compared before the cast: under a wild distortion model the point may be far off or not a number.
    const double col = std::floor((f->un[i].x() - g.min_x) / g.grid_cell_w);
    const double row = std::floor((f->un[i].y() - g.min_y) / g.grid_cell_h);
    if (col >= 0 && row >= 0 && col < FrameGeometry::kGridCols && row < FrameGeometry::kGridRows)
      f->grid[static_cast<int>(row) * FrameGeometry::kGridCols + static_cast<int>(col)].push_back(i);
  }
  return f;
}

Frame::Frame(int64_t s, double t, std::shared_ptr<const Features> feat)
    : seq(s), stamp(t), features(std::move(feat)) {
  points.assign(features->size(), nullptr);
  outlier.assign(features->size(), 0);
  moving.assign(features->size(), 0.0f);
  dynamic.assign(features->size(), 0);
  anchor.assign(features->size(), Eigen::Vector3d::Zero());
  anchored.assign(features->size(), 0);
}

int Frame::numDynamic() const {
  int n = 0;
  for (uint8_t d : dynamic) n += d != 0;
  return n;
}

void Frame::setPose(const SE3& T_world_cam) {
  T_world_cam_ = T_world_cam;
  T_cam_world_ = T_world_cam.inverse();
}

int Frame::numMatches() const {
  int n = 0;
  for (std::size_t i = 0; i < points.size(); ++i) n += points[i] && !outlier[i];
  return n;
}

void Frame::clearMatches() {
  std::fill(points.begin(), points.end(), nullptr);
  std::fill(outlier.begin(), outlier.end(), 0);
}

}  // namespace bmp::tracker

#include "mapper/keyframe_cloud.hpp"

#include <cmath>

#include <opencv2/imgproc.hpp>

namespace bmp::mapper {

cv::Mat dilateMask(const cv::Mat& mask, int margin) {
  if (mask.empty() || margin <= 0) return mask;
  const cv::Mat disc = cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * margin + 1, 2 * margin + 1));
  cv::Mat out;
  cv::dilate(mask, out, disc);
  return out;
}

PointList backProject(const KeyframeInput& kf, const RayTable& rays, const CloudSettings& settings) {
  const cv::Mat mask = dilateMask(kf.dynamic_mask, settings.mask_dilation_px);
  const double scale = 1.0 / kf.camera.depth_scale;
  const int step = settings.pixel_step;
  PointList out;
  out.reserve(static_cast<std::size_t>(kf.depth.total() / (step * step)));
  for (int v = 0; v < kf.depth.rows; v += step) {
    const auto* depth_row = kf.depth.ptr<uint16_t>(v);
    const auto* color_row = kf.color.ptr<cv::Vec3b>(v);
    const uint8_t* mask_row = mask.empty() ? nullptr : mask.ptr<uint8_t>(v);
    for (int u = 0; u < kf.depth.cols; u += step) {
      if (mask_row != nullptr && mask_row[u] != 0) continue;
      const double z = depth_row[u] * scale;
      if (z < settings.min_depth_m || z > settings.max_depth_m) continue;
      const cv::Vec2f& ray = rays.ray(u, v);
      if (!std::isfinite(ray[0]) || !std::isfinite(ray[1])) continue;  // beyond the lens model's fold
      ColoredPoint p;
      p.x = static_cast<float>(ray[0] * z);
      p.y = static_cast<float>(ray[1] * z);
      p.z = static_cast<float>(z);
      p.b = color_row[u][0];
      p.g = color_row[u][1];
      p.r = color_row[u][2];
      out.push_back(p);
    }
  }
  return out;
}

}  // namespace bmp::mapper

#include "bmp/common/camera_config.hpp"

#include <string>

namespace bmp {

CameraIntrinsics cameraFromConfig(const Config& c) {
  CameraIntrinsics k;
  k.width = c.require<int>("width");
  k.height = c.require<int>("height");
  k.fx = c.require<double>("fx");
  k.fy = c.require<double>("fy");
  k.cx = c.require<double>("cx");
  k.cy = c.require<double>("cy");
  const auto d = c.require<std::vector<double>>("distortion");
  if (d.size() != 5)
    throw ConfigError(c.origin() + ": key '" + c.path("distortion") +
                      "' must list 5 values (k1, k2, p1, p2, k3), got " + std::to_string(d.size()));
  for (int i = 0; i < 5; ++i) k.distortion[i] = d[i];
  k.depth_scale = c.require<double>("depth_scale");
  if (k.width <= 0 || k.height <= 0 || k.fx <= 0 || k.fy <= 0 || k.depth_scale <= 0)
    throw ConfigError(c.origin() + ": camera '" + c.path("") +
                      "' needs positive size, focal lengths and depth_scale");
  return k;
}

}  // namespace bmp

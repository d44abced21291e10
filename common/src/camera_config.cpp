#include "bmp/common/camera_config.hpp"

#include <cmath>
#include <sstream>
#include <string>
#include <utility>

namespace bmp {

namespace {

std::string number(double v) {
  std::ostringstream text;
  text << v;
  return text.str();
}

// Each impossible value named by its key and file: a principal point outside the image (cx: 5000 for a
// 640-wide one) still tracks, and gives a trajectory metres off without a word.
void checkIntrinsics(const Config& c, const CameraIntrinsics& k) {
  const std::string sides = "must be 1 to " + std::to_string(kMaxImageSide) + " pixels, got ";
  c.check(k.width > 0 && k.width <= kMaxImageSide, "width", sides + std::to_string(k.width));
  c.check(k.height > 0 && k.height <= kMaxImageSide, "height", sides + std::to_string(k.height));
  const std::string size = imageSizeProblem(k.width, k.height);
  c.check(size.empty(), "height", size);
  // NaN fails every comparison, so !(v > 0) refuses it too.
  for (const auto& [key, v] :
       {std::pair<const char*, double>{"fx", k.fx}, {"fy", k.fy}, {"depth_scale", k.depth_scale}})
    c.check(std::isfinite(v) && v > 0, key, "must be a positive number, got " + number(v));
  const std::string focal = focalLengthProblem(k);
  c.check(focal.empty(), "fx", focal);
  c.check(std::isfinite(k.cx) && k.cx >= 0 && k.cx <= k.width, "cx",
          "must lie inside the image (0 to width " + std::to_string(k.width) + "), got " + number(k.cx));
  c.check(std::isfinite(k.cy) && k.cy >= 0 && k.cy <= k.height, "cy",
          "must lie inside the image (0 to height " + std::to_string(k.height) + "), got " + number(k.cy));
  for (double d : k.distortion) {
    c.check(std::isfinite(d), "distortion", "must hold finite numbers");
    c.check(std::abs(d) <= kMaxDistortionCoefficient, "distortion",
            "coefficients must lie within +-10 (a lens's)");
  }
  const std::string fold = undistortionProblem(k);
  c.check(fold.empty(), "distortion", fold);
}

}  // namespace

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
  checkIntrinsics(c, k);
  return k;
}

}  // namespace bmp

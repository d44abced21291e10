#include "bmp/lcm/camera_pin.hpp"

#include <sstream>

namespace bmp {

namespace {

bool sameCamera(const camera_t& x, double x_scale, const camera_t& y, double y_scale) {
  bool same = x.width == y.width && x.height == y.height && x.fx == y.fx && x.fy == y.fy && x.cx == y.cx &&
              x.cy == y.cy && x_scale == y_scale;
  for (int i = 0; i < 5; ++i) same = same && x.distortion[i] == y.distortion[i];
  return same;
}

}  // namespace

CameraPin::Fit CameraPin::fit(const camera_t& camera, double depth_scale) const {
  if (!pinned_) return Fit::kFirst;
  if (sameCamera(pinned_->camera, pinned_->depth_scale, camera, depth_scale)) return Fit::kSame;
  return settled() ? Fit::kRefused : Fit::kReplaces;
}

void CameraPin::pin(const camera_t& camera, double depth_scale) {
  pinned_ = Pinned{camera, depth_scale};
  uses_ = 0;
}

std::string CameraPin::describe(const camera_t& c, double depth_scale) {
  std::ostringstream s;
  s << c.width << "x" << c.height << " fx " << c.fx << " fy " << c.fy << " cx " << c.cx << " cy " << c.cy
    << " depth scale " << depth_scale;
  return s.str();
}

std::string CameraPin::describe() const {
  return pinned_ ? describe(pinned_->camera, pinned_->depth_scale) : "no camera";
}

std::string CameraPin::refusal(const camera_t& camera, double depth_scale) const {
  return "camera changed mid-run, from " + describe() + " to " + describe(camera, depth_scale) +
         "; restart this process to use another camera";
}

std::string CameraPin::replacement(const camera_t& camera, double depth_scale) const {
  return "camera " + describe(camera, depth_scale) + " replaces " + describe() + ", which came with only " +
         std::to_string(uses_) + " message(s); starting again with this one";
}

}  // namespace bmp

#include "capture/synthetic_source.hpp"

#include <utility>

namespace bmp::capture {

SyntheticSource::SyntheticSource(const SyntheticSceneConfig& config)
    : scene_(std::make_shared<const SyntheticScene>(config)) {}

SyntheticSource::SyntheticSource(std::shared_ptr<const SyntheticScene> scene) : scene_(std::move(scene)) {}

std::optional<CapturedFrame> SyntheticSource::next() {
  if (next_index_ >= scene_->numFrames()) return std::nullopt;
  SyntheticFrame f = scene_->render(next_index_);
  CapturedFrame out;
  out.index = next_index_++;
  out.stamp = f.stamp;
  out.depth_stamp = f.stamp;  // rendered together: perfectly synchronised
  out.color = encodeImage(f.bgr, ImageEncoding::kRaw);
  out.depth = encodeImage(f.depth, ImageEncoding::kRaw);
  out.T_world_cam_true = f.T_world_cam;
  out.dynamic_mask = f.mask;
  return out;
}

std::string SyntheticSource::name() const {
  const auto& c = scene_->config();
  return "synthetic(" + toString(c.scenario) + ", seed " + std::to_string(c.seed) + ", " +
         std::to_string(scene_->movingObjects(0).size()) + " moving objects)";
}

}  // namespace bmp::capture

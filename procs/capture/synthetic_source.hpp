#pragma once
// The synthetic scene as a FrameSource: raw colour and depth, exact ground truth and dynamic masks.
#include <memory>

#include "capture/frame_source.hpp"
#include "capture/synthetic_scene.hpp"

namespace bmp::capture {

class SyntheticSource : public FrameSource {
 public:
  explicit SyntheticSource(const SyntheticSceneConfig& config);
  explicit SyntheticSource(std::shared_ptr<const SyntheticScene> scene);

  std::optional<CapturedFrame> next() override;
  const CameraIntrinsics& camera() const override { return scene_->camera(); }
  std::string name() const override;
  int64_t size() const override { return scene_->numFrames(); }
  const SkipReport& skips() const override { return skips_; }  // always empty: nothing can be corrupt
  const SyntheticScene& scene() const { return *scene_; }

 private:
  std::shared_ptr<const SyntheticScene> scene_;
  int next_index_ = 0;
  SkipReport skips_;
};

}  // namespace bmp::capture

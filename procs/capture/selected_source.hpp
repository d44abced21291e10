#pragma once
// --start/--end/--every for any FrameSource, by the frames' own index (TumSource selects natively, without
// reading the files it skips; this serves sources where producing a frame is cheap, like the synthetic
// scene).
#include <memory>

#include "capture/frame_source.hpp"
#include "capture/tum_source.hpp"

namespace bmp::capture {

class SelectedSource : public FrameSource {
 public:
  SelectedSource(std::unique_ptr<FrameSource> inner, FrameSelection selection);
  std::optional<CapturedFrame> next() override;
  const CameraIntrinsics& camera() const override { return inner_->camera(); }
  std::string name() const override { return inner_->name(); }
  int64_t size() const override;
  const SkipReport& skips() const override { return inner_->skips(); }

 private:
  std::unique_ptr<FrameSource> inner_;
  FrameSelection selection_;
};

}  // namespace bmp::capture

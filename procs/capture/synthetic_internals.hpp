#pragma once
// What a SyntheticScene precomputes, shared by its construction and its renderer.
#include <vector>

#include "capture/synthetic_geometry.hpp"
#include "capture/synthetic_sampler.hpp"
#include "capture/synthetic_scene.hpp"
#include "capture/synthetic_texture.hpp"

namespace bmp::capture {

struct SyntheticScene::Internals {
  std::vector<synth::SurfaceTexture> textures;  // 6 per box: room, furniture, then moving objects
  std::vector<synth::WalkPath> paths;
  synth::CameraMotion motion;
  cv::Mat noise;  // unit normal samples; a frame reads it at a per-frame offset below kNoiseMargin
  static constexpr int kNoiseMargin = 64;
};

}  // namespace bmp::capture

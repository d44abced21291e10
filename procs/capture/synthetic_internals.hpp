#pragma once
// What a SyntheticScene precomputes, shared by its construction and its renderer.
#include <vector>

#include "capture/synthetic_geometry.hpp"
#include "capture/synthetic_people.hpp"
#include "capture/synthetic_sampler.hpp"
#include "capture/synthetic_scenarios.hpp"
#include "capture/synthetic_scene.hpp"
#include "capture/synthetic_texture.hpp"

namespace bmp::capture {

struct SyntheticScene::Internals {
  // 6 per box (room, furniture, box movers), 1 per person mover; room and furniture first.
  std::vector<synth::SurfaceTexture> textures;
  std::vector<synth::WalkPath> paths;        // the boxes scenario's walkers
  synth::ScenarioCast cast;                  // every other scenario's movers
  std::vector<synth::PersonCutout> cutouts;  // by person look (ScenarioCast::looks)
  std::vector<int> mover_texture;            // first texture of each mover, in id order
  synth::CameraMotion motion;
  cv::Mat noise;  // unit normal samples; a frame reads it at a per-frame offset below kNoiseMargin
  static constexpr int kNoiseMargin = 64;
};

}  // namespace bmp::capture

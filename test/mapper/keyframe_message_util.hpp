#pragma once
// A hand-made keyframe as the tracker would publish it (JPEG colour, PNG depth and mask).
#include <bmp/keyframe_t.hpp>

#include "bmp/common/image_codec.hpp"
#include "bmp/lcm/conversions.hpp"
#include "mapper/keyframe_input.hpp"

namespace bmp::mapper::test {

inline keyframe_t keyframeMessage(const KeyframeInput& kf) {
  keyframe_t m;
  m.utime = static_cast<int64_t>(kf.stamp * 1e6) + 1000000;
  m.id = kf.id;
  m.seq = kf.id;
  m.T_world_cam = toMsg(kf.T_world_cam);
  m.camera = toMsg(kf.camera);
  m.depth_scale = kf.camera.depth_scale;
  m.color = toMsg(encodeImage(kf.color, ImageEncoding::kJpeg));
  m.depth = toMsg(encodeImage(kf.depth, ImageEncoding::kPng));
  m.dynamic_mask = toMsg(encodeImage(kf.dynamic_mask, ImageEncoding::kPng));
  return m;
}

}  // namespace bmp::mapper::test

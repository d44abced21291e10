#include "capture/synthetic_config.hpp"

#include <string>
#include <vector>

namespace bmp::capture {
namespace {

std::array<double, 3> triple(const Config& c, const std::string& key, const std::array<double, 3>& fallback) {
  const auto v = c.get<std::vector<double>>(key, {fallback.begin(), fallback.end()});
  if (v.size() != 3)
    throw ConfigError(c.origin() + ": key '" + c.path(key) + "' must list 3 numbers, got " +
                      std::to_string(v.size()));
  return {v[0], v[1], v[2]};
}

// people: a mapping of named entries {image, rect: [x, y, w, h], height_m}, in file order.
std::vector<PersonSource> people(const Config& list) {
  std::vector<PersonSource> out;
  for (const std::string& name : list.keys()) {
    const Config entry = list.section(name);
    PersonSource p;
    p.image = entry.require<std::string>("image");
    const auto rect = entry.require<std::vector<int>>("rect");
    entry.check(rect.size() == 4 && rect[2] > 0 && rect[3] > 0, "rect",
                "must be [x, y, width, height] with a positive size");
    p.rect = {rect[0], rect[1], rect[2], rect[3]};
    p.height_m = entry.get("height_m", p.height_m);
    entry.check(p.height_m > 0.5 && p.height_m <= 2.5, "height_m", "must be in (0.5, 2.5] m");
    out.push_back(p);
  }
  return out;
}

}  // namespace

SyntheticSceneConfig syntheticSceneFromConfig(const Config& s) {
  SyntheticSceneConfig c;
  const Config cam = s.section("camera");
  c.camera.width = cam.get("width", c.camera.width);
  c.camera.height = cam.get("height", c.camera.height);
  c.camera.fx = cam.get("fx", c.camera.fx);
  c.camera.fy = cam.get("fy", c.camera.fy);
  c.camera.cx = cam.get("cx", c.camera.cx);
  c.camera.cy = cam.get("cy", c.camera.cy);
  c.camera.depth_scale = cam.get("depth_scale", c.camera.depth_scale);

  c.num_frames = s.get("num_frames", c.num_frames);
  c.fps = s.get("fps", c.fps);
  c.start_stamp = s.get("start_stamp", c.start_stamp);
  c.seed = s.get("seed", c.seed);

  c.room_size = triple(s, "room_size", c.room_size);
  c.num_static_boxes = s.get("num_static_boxes", c.num_static_boxes);
  c.texels_per_metre = s.get("texels_per_metre", c.texels_per_metre);
  c.shapes_per_square_metre = s.get("shapes_per_square_metre", c.shapes_per_square_metre);

  c.camera_centre = triple(s, "camera_centre", c.camera_centre);
  c.camera_amplitude = triple(s, "camera_amplitude", c.camera_amplitude);
  c.camera_period = triple(s, "camera_period", c.camera_period);
  c.base_pitch_deg = s.get("base_pitch_deg", c.base_pitch_deg);
  c.rotation_amplitude_deg = triple(s, "rotation_amplitude_deg", c.rotation_amplitude_deg);
  c.rotation_period = triple(s, "rotation_period", c.rotation_period);
  c.camera_ramp_s = s.get("camera_ramp_s", c.camera_ramp_s);

  const std::string scenario = s.get<std::string>("scenario", toString(c.scenario));
  try {
    c.scenario = parseScenario(scenario);
  } catch (const std::invalid_argument& e) {
    throw ConfigError(s.origin() + ": key '" + s.path("scenario") + "': " + e.what());
  }
  c.num_moving_objects = s.get("num_moving_objects", c.num_moving_objects);
  c.object_size = triple(s, "object_size", c.object_size);
  c.walk_speed = s.get("walk_speed", c.walk_speed);
  if (s.has("people")) c.people = people(s.section("people"));

  c.max_depth = s.get("max_depth", c.max_depth);
  c.depth_noise = s.get("depth_noise", c.depth_noise);
  c.color_noise = s.get("color_noise", c.color_noise);
  c.exposure_s = s.get("exposure_s", c.exposure_s);
  c.exposure_samples = s.get("exposure_samples", c.exposure_samples);
  return c;
}

}  // namespace bmp::capture

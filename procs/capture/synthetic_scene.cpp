#include "capture/synthetic_scene.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "capture/synthetic_internals.hpp"

namespace bmp::capture {

using synth::SurfaceTexture;

namespace {

// Baked-in shading per face (x-, x+, y-, y+, floor/bottom, ceiling/top): fixed, so colour is view
// independent and photometric tracking holds exactly.
constexpr double kFaceShade[6] = {0.95, 0.9, 0.93, 1.0, 0.88, 0.85};

void addBoxTextures(const AlignedBox& box, const SyntheticSceneConfig& c, uint64_t seed,
                    std::vector<SurfaceTexture>& out) {
  for (int face = 0; face < 6; ++face) {
    const Eigen::Vector2d extent = synth::faceExtent(box, face);
    synth::TextureStyle style;
    style.texels_per_metre = c.texels_per_metre;
    style.shapes_per_square_metre = c.shapes_per_square_metre;
    style.brightness = kFaceShade[face];
    out.emplace_back(synth::drawTexture(extent.x(), extent.y(), style, synth::mixSeed(seed, face)),
                     c.texels_per_metre);
  }
}

// A box mover in its own frame: x forward (depth), y left (width), z up.
AlignedBox boxMoverBox(const SyntheticSceneConfig& c) {
  AlignedBox b;
  b.lo = {-c.object_size[1] / 2, -c.object_size[0] / 2, 0.0};
  b.hi = {c.object_size[1] / 2, c.object_size[0] / 2, c.object_size[2]};
  return b;
}

void validate(const SyntheticSceneConfig& c) {
  const auto fail = [](const std::string& what) { throw std::invalid_argument("synthetic scene: " + what); };
  if (c.camera.width <= 0 || c.camera.height <= 0 || c.camera.fx <= 0 || c.camera.fy <= 0 ||
      c.camera.depth_scale <= 0)
    fail("camera needs positive size, focal lengths and depth_scale");
  if (c.num_frames < 0) fail("num_frames must not be negative");
  if (c.fps <= 0) fail("fps must be positive");
  if (c.texels_per_metre < 10 || c.texels_per_metre > 2000) fail("texels_per_metre must be in [10, 2000]");
  if (c.shapes_per_square_metre < 0) fail("shapes_per_square_metre must not be negative");
  if (c.num_moving_objects < 0) fail("num_moving_objects must not be negative");
  if (c.scenario == SyntheticScenario::kPeopleWalking && c.num_moving_objects > 3)
    fail("people_walking takes at most 3 people (num_moving_objects)");
  if (c.scenario != SyntheticScenario::kBoxes && c.people.empty())
    fail("scenario " + toString(c.scenario) + " needs at least one entry in 'people'");
  for (const auto& p : c.people)
    if (p.height_m <= 0.5 || p.height_m > 2.5) fail("a person's height must be in (0.5, 2.5] m");
  for (double s : c.object_size)
    if (s <= 0) fail("object_size must be positive");
  if (c.max_depth <= 0 || c.max_depth * c.camera.depth_scale > 65535)
    fail("max_depth * depth_scale must fit 16 bits");
  if (c.depth_noise < 0 || c.color_noise < 0) fail("noise levels must not be negative");
  if (c.camera_ramp_s < 0) fail("camera_ramp_s must be >= 0");
  if (c.exposure_s < 0 || c.exposure_s * c.fps > 1.0)
    fail("exposure_s must be in [0, 1 / fps]: a frame's exposure cannot outlast it");
  if (c.exposure_samples < 2 || c.exposure_samples > 64) fail("exposure_samples must be in [2, 64]");
}

}  // namespace

SyntheticScene::SyntheticScene(const SyntheticSceneConfig& config)
    : config_(config), in_(std::make_unique<Internals>()) {
  validate(config_);
  room_ = synth::roomBox(config_.room_size);
  for (int i = 0; i < 3; ++i) {
    const double reach = std::abs(config_.camera_amplitude[i]) + 0.1;
    if (config_.camera_centre[i] - reach < room_.lo[i] || config_.camera_centre[i] + reach > room_.hi[i])
      throw std::invalid_argument("synthetic scene: the camera path leaves the room");
  }
  static_boxes_ = synth::furnitureLayout(room_, config_.num_static_boxes);
  const auto seed = static_cast<uint64_t>(config_.seed);
  addBoxTextures(room_, config_, synth::mixSeed(seed, 10), in_->textures);
  for (std::size_t i = 0; i < static_boxes_.size(); ++i)
    addBoxTextures(static_boxes_[i], config_, synth::mixSeed(seed, 11, i), in_->textures);
  if (config_.scenario == SyntheticScenario::kBoxes)
    buildBoxWalkers();
  else
    buildCast();
  in_->motion = synth::cameraMotion(config_);
  if (config_.color_noise > 0 || config_.depth_noise > 0)
    in_->noise =
        synth::unitNoiseTile(config_.camera.height + Internals::kNoiseMargin,
                             3 * config_.camera.width + Internals::kNoiseMargin, synth::mixSeed(seed, 3));
}

// The boxes scenario's walkers, exactly as before scenarios existed, so its frames stay reproducible.
void SyntheticScene::buildBoxWalkers() {
  const auto seed = static_cast<uint64_t>(config_.seed);
  in_->paths = synth::walkPaths(config_, room_);
  for (int k = 0; k < config_.num_moving_objects; ++k) {
    in_->mover_texture.push_back(static_cast<int>(in_->textures.size()));
    addBoxTextures(synth::walkerAt(in_->paths[k], config_, 0.0).box, config_, synth::mixSeed(seed, 12, k),
                   in_->textures);
  }
}

// A scripted scenario: people cut out once per photo (mirrored copies for reuse), boxes textured as ever.
void SyntheticScene::buildCast() {
  const auto seed = static_cast<uint64_t>(config_.seed);
  in_->cast = synth::scenarioCast(config_);
  std::vector<std::unique_ptr<synth::PersonCutout>> cut(config_.people.size());
  for (const auto& look : in_->cast.looks) {
    auto& base = cut[static_cast<std::size_t>(look.person)];
    if (!base) base = std::make_unique<synth::PersonCutout>(synth::cutOutPerson(config_.people[look.person]));
    in_->cutouts.push_back(look.mirror ? synth::mirrored(*base) : *base);
  }
  for (std::size_t k = 0; k < in_->cast.movers.size(); ++k) {
    const auto& m = in_->cast.movers[k];
    in_->mover_texture.push_back(static_cast<int>(in_->textures.size()));
    if (m.kind == MoverKind::kPerson) {
      const auto& c = in_->cutouts[static_cast<std::size_t>(m.look)];
      in_->textures.emplace_back(c.bgr, c.texels_per_metre);
    } else {
      addBoxTextures(boxMoverBox(config_), config_, synth::mixSeed(seed, 12, k), in_->textures);
    }
  }
}

SyntheticScene::~SyntheticScene() = default;
SyntheticScene::SyntheticScene(SyntheticScene&&) noexcept = default;
SyntheticScene& SyntheticScene::operator=(SyntheticScene&&) noexcept = default;

double SyntheticScene::stamp(int index) const {
  // Whole microseconds, so the stamp survives the 6-decimal TUM text formats exactly.
  return config_.start_stamp + std::round(1e6 * index / config_.fps) * 1e-6;
}

SE3 SyntheticScene::cameraPose(int index) const {
  return synth::cameraPoseAt(config_, in_->motion, index / config_.fps);
}

Trajectory SyntheticScene::groundTruth() const {
  Trajectory out;
  for (int i = 0; i < numFrames(); ++i) out.push_back({stamp(i), cameraPose(i)});
  return out;
}

std::vector<MovingObjectState> SyntheticScene::movingObjects(int index) const {
  return movingObjectsAt(index / config_.fps);
}

std::vector<MovingObjectState> SyntheticScene::movingObjectsAt(double t) const {
  std::vector<MovingObjectState> out;
  for (const auto& path : in_->paths) {
    out.push_back(synth::walkerAt(path, config_, t));
    out.back().info.id = static_cast<int>(out.size());
  }
  if (in_->cast.movers.empty()) return out;
  const Eigen::Vector3d eye = synth::cameraPoseAt(config_, in_->motion, t).translation();
  for (const auto& m : in_->cast.movers) {
    const synth::ScriptState st = synth::scriptAt(m, t);
    MovingObjectState s;
    s.position = st.p;
    s.info = {static_cast<int>(out.size()) + 1, m.kind, st.moving};
    if (m.kind == MoverKind::kPerson) {
      // A billboard turned about z to face the camera, so the photo is always seen from the front.
      const auto& c = in_->cutouts[static_cast<std::size_t>(m.look)];
      s.yaw = std::atan2(eye.y() - st.p.y(), eye.x() - st.p.x());
      s.box.lo = {0.0, -c.width_m / 2, 0.0};
      s.box.hi = {0.0, c.width_m / 2, c.height_m};
    } else {
      s.yaw = st.heading;
      s.box = boxMoverBox(config_);
    }
    s.T_world_object.linear() = Eigen::AngleAxisd(s.yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    s.T_world_object.translation() = Eigen::Vector3d(st.p.x(), st.p.y(), 0.0);
    out.push_back(s);
  }
  return out;
}

}  // namespace bmp::capture

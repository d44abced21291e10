#include "capture/synthetic_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "capture/synthetic_texture.hpp"

namespace bmp::capture::synth {
namespace {

AlignedBox box(double x0, double x1, double y0, double y1, double z0, double z1) {
  AlignedBox b;
  b.lo = {x0, y0, z0};
  b.hi = {x1, y1, z1};
  return b;
}

double degToRad(double deg) {
  return deg * kPi / 180.0;
}

}  // namespace

AlignedBox roomBox(const std::array<double, 3>& size) {
  if (size[0] < 4.0 || size[1] < 4.0 || size[2] < 2.2)
    throw std::invalid_argument("synthetic scene: room_size must be at least 4 x 4 x 2.2 m, got " +
                                std::to_string(size[0]) + " x " + std::to_string(size[1]) + " x " +
                                std::to_string(size[2]));
  return box(-size[0] / 2, size[0] / 2, -size[1] / 2, size[1] / 2, 0.0, size[2]);
}

std::vector<AlignedBox> furnitureLayout(const AlignedBox& r, int count) {
  const Eigen::Vector3d& lo = r.lo;
  const Eigen::Vector3d& hi = r.hi;
  const std::vector<AlignedBox> all{
      box(lo.x() + 0.8, lo.x() + 1.8, hi.y() - 0.6, hi.y(), 0.0, 0.9),   // cabinet, far wall
      box(hi.x() - 1.4, hi.x() - 0.6, hi.y() - 0.45, hi.y(), 0.0, 2.0),  // shelf, far wall
      box(lo.x(), lo.x() + 0.45, -0.5, 0.7, 0.0, 0.75),                  // bench, left wall
      box(hi.x() - 0.5, hi.x(), -1.0, 0.2, 0.0, 1.2),                    // cupboard, right wall
      box(-0.1, 0.5, hi.y() - 0.5, hi.y() - 0.1, 0.0, 0.5),              // crate, far wall
  };
  return {all.begin(), all.begin() + std::clamp(count, 0, static_cast<int>(all.size()))};
}

std::vector<WalkPath> walkPaths(const SyntheticSceneConfig& config, const AlignedBox& room) {
  // Between the camera's reach and the far furniture, clear of the side walls.
  const double margin = 0.6 + 0.5 * std::hypot(config.object_size[0], config.object_size[1]);
  const double x0 = room.lo.x() + margin, x1 = room.hi.x() - margin;
  const double y0 =
      std::max(room.lo.y() + margin,
               config.camera_centre[1] + std::abs(config.camera_amplitude[1]) + 0.9 + margin / 2);
  const double y1 = std::max(y0 + 0.4, room.hi.y() - margin - 0.3);
  SplitMix64 rng(mixSeed(static_cast<uint64_t>(config.seed), 2));
  std::vector<WalkPath> paths;
  for (int k = 0; k < config.num_moving_objects; ++k) {
    WalkPath p;
    p.rx = 0.5 * (x1 - x0) * rng.uniform(0.55, 0.95);
    p.ry = 0.5 * (y1 - y0) * rng.uniform(0.45, 0.95);
    p.centre.x() = rng.uniform(x0 + p.rx, x1 - p.rx);
    p.centre.y() = rng.uniform(y0 + p.ry, y1 - p.ry);
    // Spread the walkers around their loops so they do not start together.
    p.phase = 2 * kPi * (k + rng.uniform(0.0, 0.5)) / std::max(1, config.num_moving_objects);
    p.direction = (k % 2 == 0) ? 1.0 : -1.0;
    paths.push_back(p);
  }
  return paths;
}

MovingObjectState walkerAt(const WalkPath& path, const SyntheticSceneConfig& config, double t) {
  const double r_eff = std::sqrt(0.5 * (path.rx * path.rx + path.ry * path.ry));
  const double theta = path.phase + path.direction * config.walk_speed * t / r_eff;
  MovingObjectState s;
  s.position = path.centre + Eigen::Vector2d(path.rx * std::cos(theta), path.ry * std::sin(theta));
  // Face along the walking direction (the tangent of the ellipse).
  s.yaw = std::atan2(path.direction * path.ry * std::cos(theta), -path.direction * path.rx * std::sin(theta));
  s.T_world_object = SE3::Identity();
  s.T_world_object.linear() = Eigen::AngleAxisd(s.yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  s.T_world_object.translation() = Eigen::Vector3d(s.position.x(), s.position.y(), 0.0);
  const auto& size = config.object_size;
  s.box.lo = {-size[1] / 2, -size[0] / 2, 0.0};  // x forward (depth), y left (width)
  s.box.hi = {size[1] / 2, size[0] / 2, size[2]};
  return s;
}

CameraMotion cameraMotion(const SyntheticSceneConfig& config) {
  SplitMix64 rng(mixSeed(static_cast<uint64_t>(config.seed), 1));
  CameraMotion m;
  for (double& p : m.phase) p = rng.uniform(0, 2 * kPi);
  return m;
}

SE3 cameraPoseAt(const SyntheticSceneConfig& c, const CameraMotion& m, double t) {
  // A camera ramped in starts at rest, as a hand-held one usually does (smoothstep: no jump in velocity).
  const double x = c.camera_ramp_s > 0 ? std::clamp(t / c.camera_ramp_s, 0.0, 1.0) : 1.0;
  const double ramp = x * x * (3 - 2 * x);
  const auto wave = [&](double amplitude, double period, double phase) {
    return period > 0 ? ramp * amplitude * std::sin(2 * kPi * t / period + phase) : 0.0;
  };
  Eigen::Vector3d position;
  for (int i = 0; i < 3; ++i)
    position[i] = c.camera_centre[i] + wave(c.camera_amplitude[i], c.camera_period[i], m.phase[i]);
  const double yaw = degToRad(wave(c.rotation_amplitude_deg[0], c.rotation_period[0], m.phase[3]));
  const double pitch =
      degToRad(c.base_pitch_deg + wave(c.rotation_amplitude_deg[1], c.rotation_period[1], m.phase[4]));
  const double roll = degToRad(wave(c.rotation_amplitude_deg[2], c.rotation_period[2], m.phase[5]));
  // Looking along world +y: camera x = world x, camera y = world -z, camera z = world y.
  Eigen::Matrix3d base;
  base << 1, 0, 0, 0, 0, 1, 0, -1, 0;
  const Eigen::Matrix3d R = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix() * base *
                            Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitX()).toRotationMatrix() *
                            Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  SE3 T = SE3::Identity();
  T.linear() = R;
  T.translation() = position;
  return T;
}

Eigen::Vector2d faceExtent(const AlignedBox& b, int face) {
  int a = 0, c = 0;
  faceAxes(face, a, c);
  const Eigen::Vector3d size = b.hi - b.lo;
  return {size[a], size[c]};
}

}  // namespace bmp::capture::synth

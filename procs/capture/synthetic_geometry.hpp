#pragma once
// Geometry of the synthetic scene: room, furniture layout, walking paths and the camera path. Box faces
// are numbered 2 * axis + side, side 0 for the low coordinate and 1 for the high one.
#include <array>
#include <vector>

#include "capture/synthetic_scene.hpp"

namespace bmp::capture::synth {

// Elliptic loop walked at constant angular rate.
struct WalkPath {
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  double rx = 1.0;
  double ry = 0.5;
  double phase = 0.0;      // radians at t = 0
  double direction = 1.0;  // +1 counter-clockwise, -1 clockwise
};

struct CameraMotion {
  std::array<double, 6> phase{};  // x, y, z, yaw, pitch, roll
};

// The room with its floor at z = 0, centred on the origin in x and y. Throws std::invalid_argument for a
// room too small to hold the furniture and the walkers.
AlignedBox roomBox(const std::array<double, 3>& size);
// Up to five pieces of furniture against the walls, clear of the walking area.
std::vector<AlignedBox> furnitureLayout(const AlignedBox& room, int count);
std::vector<WalkPath> walkPaths(const SyntheticSceneConfig& config, const AlignedBox& room);
MovingObjectState walkerAt(const WalkPath& path, const SyntheticSceneConfig& config, double t);
CameraMotion cameraMotion(const SyntheticSceneConfig& config);
SE3 cameraPoseAt(const SyntheticSceneConfig& config, const CameraMotion& motion, double t);

// The two axes spanning a face: texture coordinates are metres from the box's low corner along them.
inline void faceAxes(int face, int& a, int& b) {
  const int axis = face / 2;
  a = axis == 0 ? 1 : 0;
  b = axis == 2 ? 1 : 2;
}
Eigen::Vector2d faceExtent(const AlignedBox& box, int face);

}  // namespace bmp::capture::synth

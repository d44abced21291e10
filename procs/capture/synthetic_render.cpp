// SyntheticScene::render: one ray per pixel through the pixel centre, against the room (from inside) and
// the boxes whose screen-space bounds contain the pixel.
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "capture/synthetic_internals.hpp"

namespace bmp::capture {
namespace {

// A box to test rays against, in its own frame: a ray of camera direction dc is o + t * M * dc there,
// and t is then the z-depth of the hit in the camera frame.
struct Candidate {
  AlignedBox box;
  Eigen::Matrix3d M;
  Eigen::Vector3d o;
  int texture = 0;  // first of its 6 textures
  bool dynamic = false;
  int u0 = 0, u1 = -1, v0 = 0, v1 = -1;  // inclusive pixel bounds of its projection
  // M * (0, yn, 1) for the current row, and M's first column.
  Eigen::Vector3d row_dir = Eigen::Vector3d::Zero(), col_dir = Eigen::Vector3d::Zero();
};

// Screen bounds of the box's projection; false when it lies entirely behind the camera.
bool screenBounds(Candidate& c, const CameraIntrinsics& k) {
  const Eigen::Matrix3d Mt = c.M.transpose();
  double umin = 1e9, umax = -1e9, vmin = 1e9, vmax = -1e9;
  int behind = 0;
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3d q((i & 1) ? c.box.hi.x() : c.box.lo.x(), (i & 2) ? c.box.hi.y() : c.box.lo.y(),
                            (i & 4) ? c.box.hi.z() : c.box.lo.z());
    const Eigen::Vector3d p = Mt * (q - c.o);
    if (p.z() < 1e-3) {
      ++behind;
      continue;
    }
    const double u = k.fx * p.x() / p.z() + k.cx, v = k.fy * p.y() / p.z() + k.cy;
    umin = std::min(umin, u), umax = std::max(umax, u), vmin = std::min(vmin, v), vmax = std::max(vmax, v);
  }
  if (behind == 8) return false;
  if (behind > 0) umin = vmin = -1e9, umax = vmax = 1e9;  // straddles the camera plane: test everywhere
  c.u0 = static_cast<int>(std::max(0.0, std::floor(umin) - 1));
  c.u1 = static_cast<int>(std::min(k.width - 1.0, std::ceil(umax) + 1));
  c.v0 = static_cast<int>(std::max(0.0, std::floor(vmin) - 1));
  c.v1 = static_cast<int>(std::min(k.height - 1.0, std::ceil(vmax) + 1));
  return c.u0 <= c.u1 && c.v0 <= c.v1;
}

// Slab test for a ray starting outside the box; the entry distance and face when it hits ahead.
inline bool enterBox(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const AlignedBox& b, double& t,
                     int& face) {
  double t_near = -std::numeric_limits<double>::infinity();
  double t_far = std::numeric_limits<double>::infinity();
  int axis = 0;
  for (int a = 0; a < 3; ++a) {
    if (d[a] == 0.0) {
      if (o[a] < b.lo[a] || o[a] > b.hi[a]) return false;
      continue;
    }
    const double inv = 1.0 / d[a];
    double t0 = (b.lo[a] - o[a]) * inv, t1 = (b.hi[a] - o[a]) * inv;
    if (t0 > t1) std::swap(t0, t1);
    if (t0 > t_near) t_near = t0, axis = a;
    t_far = std::min(t_far, t1);
  }
  if (t_near > t_far || t_near <= 0.0) return false;
  t = t_near;
  face = 2 * axis + (d[axis] < 0 ? 1 : 0);
  return true;
}

// Where a ray from inside the box leaves it.
inline void exitBox(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const AlignedBox& b, double& t,
                    int& face) {
  t = std::numeric_limits<double>::infinity();
  face = 0;
  for (int a = 0; a < 3; ++a) {
    if (d[a] == 0.0) continue;
    const bool up = d[a] > 0;
    const double ta = ((up ? b.hi[a] : b.lo[a]) - o[a]) / d[a];
    if (ta < t) t = ta, face = 2 * a + (up ? 1 : 0);
  }
}

}  // namespace

SyntheticFrame SyntheticScene::render(int index) const {
  if (index < 0 || index >= numFrames())
    throw std::out_of_range("synthetic scene: frame " + std::to_string(index) + " outside [0, " +
                            std::to_string(numFrames()) + ")");
  const CameraIntrinsics& k = config_.camera;
  SyntheticFrame frame;
  frame.index = index;
  frame.stamp = stamp(index);
  frame.T_world_cam = cameraPose(index);
  frame.bgr.create(k.height, k.width, CV_8UC3);
  frame.depth.create(k.height, k.width, CV_16UC1);
  frame.mask = cv::Mat::zeros(k.height, k.width, CV_8UC1);

  const Eigen::Matrix3d R = frame.T_world_cam.linear();
  const Eigen::Vector3d origin = frame.T_world_cam.translation();
  std::vector<Candidate> candidates;
  const auto add = [&](const AlignedBox& box, const SE3& T_world_box, int texture, bool dynamic) {
    Candidate c;
    c.box = box;
    c.M = T_world_box.linear().transpose() * R;
    c.o = T_world_box.inverse() * origin;
    c.texture = texture;
    c.dynamic = dynamic;
    c.col_dir = c.M.col(0);
    if (screenBounds(c, k)) candidates.push_back(c);
  };
  for (std::size_t i = 0; i < static_boxes_.size(); ++i)
    add(static_boxes_[i], SE3::Identity(), 6 + 6 * static_cast<int>(i), false);
  const auto objects = movingObjects(index);
  for (std::size_t i = 0; i < objects.size(); ++i)
    add(objects[i].box, objects[i].T_world_object, 6 * static_cast<int>(1 + static_boxes_.size() + i), true);

  // Noise offsets for this frame: colour channels and depth each read the tile at their own offset.
  synth::SplitMix64 rng(synth::mixSeed(static_cast<uint64_t>(config_.seed), 4, static_cast<uint64_t>(index)));
  int off[5];
  for (int& o : off) o = rng.integer(0, Internals::kNoiseMargin - 1);
  const bool color_noise = config_.color_noise > 0, depth_noise = config_.depth_noise > 0;
  const float color_sigma = static_cast<float>(config_.color_noise);

  const double focal = std::sqrt(k.fx * k.fy);
  std::vector<Candidate*> active;
  for (int v = 0; v < k.height; ++v) {
    const double yn = (v - k.cy) / k.fy;
    const Eigen::Vector3d row_dir = R.col(1) * yn + R.col(2);
    active.clear();
    for (auto& c : candidates) {
      if (v < c.v0 || v > c.v1) continue;
      c.row_dir = c.M.col(1) * yn + c.M.col(2);
      active.push_back(&c);
    }
    auto* bgr = frame.bgr.ptr<uint8_t>(v);
    auto* depth = frame.depth.ptr<uint16_t>(v);
    auto* mask = frame.mask.ptr<uint8_t>(v);
    const float* noise_row = color_noise || depth_noise ? in_->noise.ptr<float>(v + off[0]) : nullptr;
    for (int u = 0; u < k.width; ++u) {
      const double xn = (u - k.cx) / k.fx;
      const Eigen::Vector3d d = row_dir + xn * R.col(0);
      double t = 0.0;
      int face = 0;
      exitBox(origin, d, room_, t, face);
      const Candidate* hit = nullptr;
      Eigen::Vector3d hit_dir = d;
      for (const Candidate* c : active) {
        if (u < c->u0 || u > c->u1) continue;
        const Eigen::Vector3d dl = c->row_dir + xn * c->col_dir;
        double tc = 0.0;
        int fc = 0;
        if (enterBox(c->o, dl, c->box, tc, fc) && tc < t) t = tc, face = fc, hit = c, hit_dir = dl;
      }
      const AlignedBox& box = hit ? hit->box : room_;
      const Eigen::Vector3d p = (hit ? hit->o : origin) + t * hit_dir;
      int a = 0, b = 0;
      synth::faceAxes(face, a, b);
      // Footprint of the pixel on the surface: t / (f * sqrt(|d . n|)) for the unnormalised direction d.
      const double footprint = t / (focal * std::sqrt(std::max(std::abs(hit_dir[face / 2]), 1e-4)));
      float colour[3];
      in_->textures[(hit ? hit->texture : 0) + face].sample(p[a] - box.lo[a], p[b] - box.lo[b], footprint,
                                                            colour);
      for (int ch = 0; ch < 3; ++ch) {
        const float n = color_noise ? color_sigma * noise_row[3 * u + ch + off[1 + ch]] : 0.0f;
        bgr[3 * u + ch] = cv::saturate_cast<uint8_t>(colour[ch] + n);
      }
      double z = t;
      if (depth_noise) z += config_.depth_noise * z * z * noise_row[3 * u + off[4]];
      depth[u] = z > 0 && z <= config_.max_depth
                     ? static_cast<uint16_t>(std::min(65535.0, std::round(z * k.depth_scale)))
                     : 0;
      if (hit && hit->dynamic) mask[u] = 255;
    }
  }
  return frame;
}

}  // namespace bmp::capture

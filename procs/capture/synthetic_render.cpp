// SyntheticScene::render: one ray per pixel through the pixel centre, against the room (from inside) and
// the boxes whose screen-space bounds contain the pixel.
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <opencv2/imgproc.hpp>

#include "capture/synthetic_internals.hpp"

namespace bmp::capture {
namespace {

// A box to test rays against, in its own frame: a ray of camera direction dc is o + t * M * dc there, and t
// is then the z-depth of the hit in the camera frame. The per-pixel part works in float on corners
// relative to o; float keeps depth and texture coordinates within a few micrometres here.
struct Candidate {
  AlignedBox box;
  Eigen::Matrix3d M = Eigen::Matrix3d::Identity();
  Eigen::Vector3d o = Eigen::Vector3d::Zero();
  bool own_frame = false;  // false: the world frame, so the pixel's world ray is reused
  int texture = 0;         // first of its 6 textures (a billboard has one)
  bool dynamic = false;
  uint8_t id = 0;                                        // mover id, 0 for the static scene
  const synth::PersonCutout* cutout = nullptr;           // a billboard: drawn only where the person is
  int u0 = 0, u1 = -1, v0 = 0, v1 = -1;                  // inclusive pixel bounds of its projection
  float lo_o[3] = {0, 0, 0}, hi_o[3] = {0, 0, 0};        // box corners minus o
  float row_dir[3] = {0, 0, 0}, col_dir[3] = {0, 0, 0};  // M * (0, yn, 1) for this row; M's first column
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

// Slab test with precomputed reciprocal directions for a ray starting outside the box: the entry distance
// and face when it enters ahead of t_max.
inline bool enterBox(const float lo_o[3], const float hi_o[3], const float inv[3], float t_max, float& t,
                     int& face) {
  float t_near = 0.0f, t_far = t_max;
  int axis = -1;
  for (int a = 0; a < 3; ++a) {
    const float t0 = lo_o[a] * inv[a], t1 = hi_o[a] * inv[a];
    const float near = std::min(t0, t1), far = std::max(t0, t1);
    if (near > t_near) t_near = near, axis = a;
    t_far = std::min(t_far, far);
  }
  if (axis < 0 || t_near > t_far) return false;
  t = t_near;
  face = 2 * axis + (inv[axis] < 0 ? 1 : 0);
  return true;
}

void toFloat(const Eigen::Vector3d& v, float out[3]) {
  for (int i = 0; i < 3; ++i) out[i] = static_cast<float>(v[i]);
}

// The nearest surface along one pixel's ray: its distance (camera z), face, the box (null: the room) and the
// ray's direction in the frame of what it hit.
struct PixelHit {
  float t = std::numeric_limits<float>::infinity();
  int face = 0;
  const Candidate* box = nullptr;
  float dir[3] = {0, 0, 0};
};

// Per-frame noise: where colour channels and depth each read the noise tile, and how strong it is.
struct FrameNoise {
  int off[5] = {0, 0, 0, 0, 0};
  bool color = false, depth = false;
  float color_sigma = 0.0f, depth_sigma = 0.0f;
};

FrameNoise frameNoise(const SyntheticSceneConfig& config, int index, int margin) {
  FrameNoise n;
  synth::SplitMix64 rng(synth::mixSeed(static_cast<uint64_t>(config.seed), 4, static_cast<uint64_t>(index)));
  for (int& o : n.off) o = rng.integer(0, margin - 1);
  n.color = config.color_noise > 0, n.depth = config.depth_noise > 0;
  n.color_sigma = static_cast<float>(config.color_noise);
  n.depth_sigma = static_cast<float>(config.depth_noise);
  return n;
}

// One frame's rendering: the boxes in view, then row by row a geometry pass (ray casting, depth, mask,
// texel lookups) and a colour pass (texture samples plus noise).
class FrameRenderer {
 public:
  FrameRenderer(const SyntheticSceneConfig& config, const std::vector<synth::SurfaceTexture>& textures,
                const cv::Mat& noise, const SE3& T_world_cam, const AlignedBox& room, FrameNoise frame_noise)
      : k_(config.camera),
        textures_(textures),
        noise_(noise),
        R_(T_world_cam.linear()),
        origin_(T_world_cam.translation()),
        n_(frame_noise),
        max_depth_(static_cast<float>(config.max_depth)),
        depth_scale_(static_cast<float>(k_.depth_scale)),
        focal_(static_cast<float>(std::sqrt(k_.fx * k_.fy))),
        lookups_(k_.width) {
    toFloat(room.lo - origin_, room_lo_o_);
    toFloat(room.hi - origin_, room_hi_o_);
    toFloat(R_.col(0), r_col0_);
  }

  // A box with its first texture; movers (id > 0) move, so their rays are cast in their own frame. With a
  // cutout, the box is a flat billboard x = 0 showing that person.
  void addBox(const AlignedBox& box, const SE3& T_world_box, int texture, int id,
              const synth::PersonCutout* cutout = nullptr) {
    Candidate c;
    c.box = box;
    c.M = T_world_box.linear().transpose() * R_;
    c.o = T_world_box.inverse() * origin_;
    c.own_frame = id > 0;
    c.texture = texture;
    c.dynamic = id > 0;
    c.id = static_cast<uint8_t>(id);
    c.cutout = cutout;
    toFloat(box.lo - c.o, c.lo_o);
    toFloat(box.hi - c.o, c.hi_o);
    toFloat(c.M.col(0), c.col_dir);
    if (screenBounds(c, k_)) candidates_.push_back(c);
  }

  void renderRow(int v, SyntheticFrame& frame) {
    const double yn = (v - k_.cy) / k_.fy;
    float row_dir[3];
    toFloat(R_.col(1) * yn + R_.col(2), row_dir);
    selectRow(v, yn);
    auto* depth = frame.depth.ptr<uint16_t>(v);
    auto* mask = frame.mask.ptr<uint8_t>(v);
    auto* ids = frame.mover_ids.ptr<uint8_t>(v);
    const float* noise_row = n_.color || n_.depth ? noise_.ptr<float>(v + n_.off[0]) : nullptr;
    for (int u = 0; u < k_.width; ++u) {
      const float xn = static_cast<float>((u - k_.cx) / k_.fx);
      const PixelHit hit = castRay(u, xn, row_dir);
      lookups_[u] = locateTexel(hit);
      synth::prefetch(lookups_[u]);
      float z = hit.t;
      if (n_.depth) z += n_.depth_sigma * z * z * noise_row[3 * u + n_.off[4]];
      depth[u] = z > 0 && z <= max_depth_ ? cv::saturate_cast<uint16_t>(z * depth_scale_) : 0;
      if (hit.box && hit.box->dynamic) mask[u] = 255, ids[u] = hit.box->id;
    }
    colourRow(frame.bgr.ptr<uint8_t>(v), noise_row);
  }

 private:
  // The boxes whose projection covers row v, with their ray direction for the row.
  void selectRow(int v, double yn) {
    active_.clear();
    for (auto& c : candidates_) {
      if (v < c.v0 || v > c.v1) continue;
      toFloat(c.M.col(1) * yn + c.M.col(2), c.row_dir);
      active_.push_back(&c);
    }
  }

  PixelHit castRay(int u, float xn, const float row_dir[3]) const {
    PixelHit hit;
    float d[3], inv[3];
    for (int i = 0; i < 3; ++i) d[i] = row_dir[i] + xn * r_col0_[i], inv[i] = 1.0f / d[i];
    // The room, from inside: the nearest wall plane ahead.
    for (int a = 0; a < 3; ++a) {
      const bool up = d[a] > 0;
      const float ta = (up ? room_hi_o_[a] : room_lo_o_[a]) * inv[a];
      if (ta < hit.t) hit.t = ta, hit.face = 2 * a + (up ? 1 : 0);
    }
    for (int i = 0; i < 3; ++i) hit.dir[i] = d[i];
    for (const Candidate* c : active_) {
      if (u < c->u0 || u > c->u1) continue;
      float dl[3] = {d[0], d[1], d[2]}, invl[3] = {inv[0], inv[1], inv[2]};
      if (c->own_frame)
        for (int i = 0; i < 3; ++i) dl[i] = c->row_dir[i] + xn * c->col_dir[i], invl[i] = 1.0f / dl[i];
      float tc = 0.0f;
      int fc = 0;
      if (enterBox(c->lo_o, c->hi_o, invl, hit.t, tc, fc) && (!c->cutout || onPerson(*c, tc, dl))) {
        hit.t = tc, hit.face = fc, hit.box = c;
        for (int i = 0; i < 3; ++i) hit.dir[i] = dl[i];
      }
    }
    return hit;
  }

  // Whether a billboard's hit at distance t along d falls on the person's silhouette (nearest texel): the
  // rest of the photo is not drawn, so the ray goes on to whatever lies behind.
  static bool onPerson(const Candidate& c, float t, const float d[3]) {
    const synth::PersonCutout& p = *c.cutout;
    const float tpm = static_cast<float>(p.texels_per_metre);
    const float x = (t * d[1] - c.lo_o[1]) * tpm, y = (t * d[2] - c.lo_o[2]) * tpm;
    if (!(x >= 0.0f && y >= 0.0f && x < static_cast<float>(p.alpha.cols) &&
          y < static_cast<float>(p.alpha.rows)))
      return false;
    return p.alpha.ptr<uint8_t>(static_cast<int>(y))[static_cast<int>(x)] != 0;
  }

  synth::TexelLookup locateTexel(const PixelHit& hit) const {
    const float* lo_o = hit.box ? hit.box->lo_o : room_lo_o_;
    int a = 0, b = 0;
    synth::faceAxes(hit.face, a, b);
    // Footprint of the pixel on the surface: t / (f * sqrt(|d . n|)) for the unnormalised direction d.
    const float footprint = hit.t / (focal_ * std::sqrt(std::max(std::abs(hit.dir[hit.face / 2]), 1e-4f)));
    const int texture = hit.box ? hit.box->texture + (hit.box->cutout ? 0 : hit.face) : hit.face;
    return textures_[texture].locate(hit.t * hit.dir[a] - lo_o[a], hit.t * hit.dir[b] - lo_o[b], footprint);
  }

  // Second pass: colour, once the row's texels are on their way into the cache.
  void colourRow(uint8_t* bgr, const float* noise_row) const {
    for (int u = 0; u < k_.width; ++u) {
      float colour[3];
      synth::sample(lookups_[u], colour);
      for (int ch = 0; ch < 3; ++ch) {
        const float n = n_.color ? n_.color_sigma * noise_row[3 * u + ch + n_.off[1 + ch]] : 0.0f;
        bgr[3 * u + ch] = cv::saturate_cast<uint8_t>(colour[ch] + n);
      }
    }
  }

  const CameraIntrinsics& k_;
  const std::vector<synth::SurfaceTexture>& textures_;
  const cv::Mat& noise_;
  Eigen::Matrix3d R_;
  Eigen::Vector3d origin_;
  FrameNoise n_;
  float max_depth_, depth_scale_, focal_;
  float room_lo_o_[3] = {0, 0, 0}, room_hi_o_[3] = {0, 0, 0}, r_col0_[3] = {0, 0, 0};
  std::vector<Candidate> candidates_;
  std::vector<Candidate*> active_;
  std::vector<synth::TexelLookup> lookups_;
};

}  // namespace

SyntheticFrame SyntheticScene::render(int index) const {
  if (index < 0 || index >= numFrames())
    throw std::out_of_range("synthetic scene: frame " + std::to_string(index) + " outside [0, " +
                            std::to_string(numFrames()) + ")");
  const double t = index / config_.fps;
  SyntheticFrame frame = renderAt(index, t);
  if (config_.exposure_s <= 0.0) return frame;
  cv::Mat sum;
  frame.bgr.convertTo(sum, CV_32FC3);
  const int n = config_.exposure_samples;
  for (int j = 0; j < n; ++j) {
    const double offset = (static_cast<double>(j) / (n - 1) - 0.5) * config_.exposure_s;
    // The centre sample (odd n) is the frame already rendered.
    if (2 * j + 1 == n) continue;
    cv::accumulate(renderAt(index, t + offset).bgr, sum);
  }
  const int renders = n + (n % 2 == 0 ? 1 : 0);  // an even n adds the centre to its n samples
  sum.convertTo(frame.bgr, CV_8UC3, 1.0 / renders);
  return frame;
}

SyntheticFrame SyntheticScene::renderAt(int index, double t) const {
  const CameraIntrinsics& k = config_.camera;
  SyntheticFrame frame;
  frame.index = index;
  frame.stamp = stamp(index);
  frame.T_world_cam = synth::cameraPoseAt(config_, in_->motion, t);
  frame.bgr.create(k.height, k.width, CV_8UC3);
  frame.depth.create(k.height, k.width, CV_16UC1);
  frame.mask = cv::Mat::zeros(k.height, k.width, CV_8UC1);
  frame.mover_ids = cv::Mat::zeros(k.height, k.width, CV_8UC1);

  FrameRenderer renderer(config_, in_->textures, in_->noise, frame.T_world_cam, room_,
                         frameNoise(config_, index, Internals::kNoiseMargin));
  // Textures: 6 per box, the room's first, then the furniture's, then the movers'.
  for (std::size_t i = 0; i < static_boxes_.size(); ++i)
    renderer.addBox(static_boxes_[i], SE3::Identity(), 6 + 6 * static_cast<int>(i), 0);
  const auto objects = movingObjectsAt(t);
  for (std::size_t i = 0; i < objects.size(); ++i) {
    const MovingObjectState& o = objects[i];
    const bool person = o.info.kind == MoverKind::kPerson;
    const int look = person ? in_->cast.movers[i].look : -1;
    renderer.addBox(o.box, o.T_world_object, in_->mover_texture[i], o.info.id,
                    person ? &in_->cutouts[static_cast<std::size_t>(look)] : nullptr);
    frame.movers.push_back(o.info);
  }
  for (int v = 0; v < k.height; ++v) renderer.renderRow(v, frame);
  return frame;
}

}  // namespace bmp::capture

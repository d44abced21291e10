#include "tracker/matcher.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <unordered_set>

namespace bmp::tracker {

namespace {

// Matches whose keypoint rotation differs from the dominant ones (three most populated bins) are wrong.
class RotationHistogram {
 public:
  void add(float angle_a, float angle_b, int index) {
    float rot = angle_a - angle_b;
    if (rot < 0.0f) rot += 360.0f;
    const int bin = std::min(kBins - 1, static_cast<int>(rot * kBins / 360.0f));
    bins_[bin].push_back(index);
  }
  // Indices to drop.
  std::vector<int> outliers() const {
    std::array<std::size_t, kBins> sizes{};
    for (int i = 0; i < kBins; ++i) sizes[i] = bins_[i].size();
    std::array<int, kBins> order{};
    for (int i = 0; i < kBins; ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](int a, int b) { return sizes[a] > sizes[b]; });
    std::vector<int> out;
    const std::size_t top = sizes[order[0]];
    for (int r = 0; r < kBins; ++r) {
      const int bin = order[r];
      const bool keep = r < 3 && sizes[bin] > 0.1 * top;
      if (!keep) out.insert(out.end(), bins_[bin].begin(), bins_[bin].end());
    }
    return out;
  }

 private:
  static constexpr int kBins = 30;
  std::array<std::vector<int>, kBins> bins_;
};

bool isRealPoint(const std::shared_ptr<MapPoint>& mp) {
  return mp && !mp->bad && !mp->observations.empty();
}

// Where a point lands in a view: pixel and virtual right-image coordinate.
struct Projection {
  Eigen::Vector2d uv;
  double u_right = 0.0;
  double depth = 0.0;  // metres along the optical axis
};

// Nothing when the point is behind the camera or outside the image.
std::optional<Projection> project(const SE3& T_cam_world, const Eigen::Vector3d& p_world,
                                  const FrameGeometry& g) {
  const Eigen::Vector3d p_cam = T_cam_world * p_world;
  if (p_cam.z() <= 0.0) return std::nullopt;
  const Eigen::Vector2d uv = g.project(p_cam);
  if (!g.inBounds(uv.x(), uv.y())) return std::nullopt;
  return Projection{uv, uv.x() - g.bf / p_cam.z(), p_cam.z()};
}

// Whether the view sees the point within the distances its descriptor was made for.
bool inScaleRange(const MapPoint& mp, double dist, const MatcherOptions& m) {
  return !(dist < m.min_distance_factor * mp.min_distance || dist > m.max_distance_factor * mp.max_distance);
}

// How candidates near a projection are gated. Tracking skips keypoints that already hold a real point and
// requires a depth keypoint's right-image coordinate within the radius; fusion instead gates by the
// reprojection error (u, v and u_right against chi2), and may pick an observed keypoint (it then merges).
enum class Gate { kTracking, kReprojection };

struct SearchWindow {
  double radius = 0.0;                 // pixels
  int min_level = -1, max_level = -1;  // as Features::forEachInArea
  Gate gate = Gate::kTracking;
  const std::vector<std::shared_ptr<MapPoint>>* occupied = nullptr;  // kTracking: the view's matches
  double depth_ratio = 0.0;  // kTracking: TrackingOptions::match_depth_ratio (0: no depth gate)
  double chi2 = 0.0;         // kReprojection
};

struct SearchResult {
  int best = -1, best_dist = 256, best_level = -1;
  int second_dist = 256, second_level = -1;
};

bool passesGate(const Features& f, const FrameGeometry& g, const Projection& p, const SearchWindow& w,
                int j) {
  if (w.gate == Gate::kReprojection) {
    double e2 = (f.un[j] - p.uv).squaredNorm();
    if (f.depth[j] > 0) {
      const double eu = p.u_right - f.uRight(g, j);
      e2 += eu * eu;
    }
    return !(e2 * g.pyramid.inv_sigma2[f.level(j)] > w.chi2);
  }
  if (isRealPoint((*w.occupied)[j])) return false;
  if (f.depth[j] <= 0) return true;
  // The right-image gate scales with the pyramid level and, at a virtual baseline, barely tells 2 m from
  // 3.5 m at coarse levels: a person's keypoint took the wall point behind it, and its static history.
  if (w.depth_ratio > 0 && std::abs(f.depth[j] - p.depth) > w.depth_ratio * p.depth) return false;
  return std::abs(p.u_right - f.uRight(g, j)) <= w.radius;
}

// The keypoints nearest in descriptor to a projected point among those in the window that pass the gate.
SearchResult searchByProjection(const Features& f, const FrameGeometry& g, const Projection& p,
                                const uint8_t* descriptor, const SearchWindow& w) {
  SearchResult s;
  f.forEachInArea(g, p.uv.x(), p.uv.y(), w.radius, w.min_level, w.max_level, [&](int j) {
    if (!passesGate(f, g, p, w, j)) return;
    const int d = hamming(descriptor, f.descriptor(j));
    if (d < s.best_dist) {
      s.second_dist = s.best_dist;
      s.second_level = s.best_level;
      s.best_dist = d;
      s.best_level = f.level(j);
      s.best = j;
    } else if (d < s.second_dist) {
      s.second_dist = d;
      s.second_level = f.level(j);
    }
  });
  return s;
}

}  // namespace

int matchFromLastFrame(Frame& cur, const Frame& last, const FrameGeometry& g, const TrackingOptions& o,
                       double radius) {
  const Features& fc = *cur.features;
  const Features& fl = *last.features;
  RotationHistogram hist;
  int matches = 0;
  for (int i = 0; i < fl.size(); ++i) {
    const auto& mp = last.points[i];
    if (!mp || last.outlier[i] || mp->bad) continue;
    const auto p = project(cur.T_cam_world(), mp->p_world, g);
    if (!p) continue;
    const int level = fl.level(i);
    SearchWindow w;
    w.radius = radius * g.pyramid.scale[level];
    w.min_level = std::max(0, level - 1);
    w.max_level = level + 1;
    w.occupied = &cur.points;
    w.depth_ratio = o.match_depth_ratio;
    const SearchResult s = searchByProjection(fc, g, *p, mp->descriptor.ptr<uint8_t>(0), w);
    if (s.best < 0 || s.best_dist > o.match_threshold_high) continue;
    cur.points[s.best] = mp;
    cur.outlier[s.best] = 0;
    ++matches;
    hist.add(fl.keys[i].angle, fc.keys[s.best].angle, s.best);
  }
  if (o.check_orientation) {
    for (int j : hist.outliers()) {
      if (cur.points[j]) {
        cur.points[j].reset();
        --matches;
      }
    }
  }
  return matches;
}

int matchLocalPoints(Frame& cur, const std::vector<std::shared_ptr<MapPoint>>& points, const FrameGeometry& g,
                     const TrackingOptions& o, const MatcherOptions& m, double radius) {
  const Features& f = *cur.features;
  std::unordered_set<const MapPoint*> already;
  for (const auto& mp : cur.points)
    if (mp) already.insert(mp.get());
  const Eigen::Vector3d center = cur.center();
  int matches = 0;
  for (const auto& mp : points) {
    if (mp->bad || already.count(mp.get())) continue;
    const auto p = project(cur.T_cam_world(), mp->p_world, g);
    if (!p) continue;
    const Eigen::Vector3d ray = mp->p_world - center;
    const double dist = ray.norm();
    if (!inScaleRange(*mp, dist, m)) continue;
    const double view_cos = ray.dot(mp->normal) / dist;
    if (view_cos < m.min_view_cos) continue;
    ++mp->visible;
    const int level = mp->predictLevel(dist, g);
    SearchWindow w;
    // A wider window when the point is seen from a direction far from its usual one.
    w.radius = radius * g.pyramid.scale[level] * (view_cos > m.narrow_view_cos ? 1.0 : m.wide_window_factor);
    w.min_level = level - 1;
    w.max_level = level;
    w.occupied = &cur.points;
    w.depth_ratio = o.match_depth_ratio;
    const SearchResult s = searchByProjection(f, g, *p, mp->descriptor.ptr<uint8_t>(0), w);
    if (s.best < 0 || s.best_dist > o.match_threshold_high) continue;
    if (s.best_level == s.second_level && s.best_dist > o.local_match_ratio * s.second_dist) continue;
    cur.points[s.best] = mp;
    cur.outlier[s.best] = 0;
    ++matches;
  }
  return matches;
}

int matchByDescriptors(const Features& f, const std::vector<std::shared_ptr<MapPoint>>& points, double ratio,
                       int max_distance, std::vector<std::shared_ptr<MapPoint>>& matches) {
  std::vector<int> best_for_key(f.size(), 256);
  std::vector<std::shared_ptr<MapPoint>> chosen(f.size());
  for (const auto& mp : points) {
    if (!mp || mp->bad) continue;
    ClosestTwo c;
    const uint8_t* d_mp = mp->descriptor.ptr<uint8_t>(0);
    for (int j = 0; j < f.size(); ++j)
      if (!f.excluded[j]) c.offer(j, hamming(d_mp, f.descriptor(j)));
    if (c.best < 0 || c.best_dist > max_distance || c.best_dist > ratio * c.second_dist) continue;
    if (c.best_dist < best_for_key[c.best]) {
      best_for_key[c.best] = c.best_dist;
      chosen[c.best] = mp;
    }
  }
  int n = 0;
  for (int j = 0; j < f.size(); ++j) {
    if (chosen[j] && !matches[j]) {
      matches[j] = chosen[j];
      ++n;
    }
  }
  return n;
}

int fusePoints(Map& map, KeyFrame* kf, const std::vector<std::shared_ptr<MapPoint>>& points,
               const FrameGeometry& g, const MatcherOptions& m, double radius, double chi2) {
  const Features& f = *kf->features;
  const Eigen::Vector3d center = kf->center();
  int fused = 0;
  for (const auto& mp : points) {
    if (!mp || mp->bad || mp->observations.count(kf)) continue;
    const auto p = project(kf->T_cam_world(), mp->p_world, g);
    if (!p) continue;
    const Eigen::Vector3d ray = mp->p_world - center;
    const double dist = ray.norm();
    if (!inScaleRange(*mp, dist, m)) continue;
    if (ray.dot(mp->normal) < m.min_view_cos * dist) continue;
    const int level = mp->predictLevel(dist, g);
    SearchWindow w;
    w.radius = radius * g.pyramid.scale[level];
    w.min_level = std::max(0, level - 1);
    w.max_level = level;
    w.gate = Gate::kReprojection;
    w.chi2 = chi2;
    const SearchResult s = searchByProjection(f, g, *p, mp->descriptor.ptr<uint8_t>(0), w);
    // A keypoint on a mover takes no static point: its observation would join the point's in local BA.
    if (s.best < 0 || s.best_dist > m.fuse_max_distance || kf->dynamic[s.best]) continue;
    const auto existing = kf->points[s.best];
    if (existing && !existing->bad) {
      if (existing->observations.size() >= mp->observations.size())
        map.replacePoint(mp, existing);
      else
        map.replacePoint(existing, mp);
    } else {
      map.addObservation(kf, s.best, mp);
    }
    ++fused;
  }
  return fused;
}

std::vector<std::pair<int, int>> matchForTriangulation(const KeyFrame& kf1, const KeyFrame& kf2,
                                                       const FrameGeometry& g, int max_distance, double ratio,
                                                       double epipolar_chi2) {
  const Features& f1 = *kf1.features;
  const Features& f2 = *kf2.features;
  // Essential matrix from kf1's normalised coordinates to kf2's: x2^T E x1 = 0.
  const SE3 T21 = kf2.T_cam_world() * kf1.T_world_cam();
  const Eigen::Matrix3d E = skew(T21.translation()) * T21.rotation();
  std::vector<int> cand2;
  for (int j = 0; j < f2.size(); ++j)
    if (!f2.excluded[j] && !kf2.points[j]) cand2.push_back(j);
  std::vector<std::pair<int, int>> out;
  std::vector<int> taken(f2.size(), -1);
  std::vector<int> taken_dist(f2.size(), 256);
  for (int i = 0; i < f1.size(); ++i) {
    if (f1.excluded[i] || kf1.points[i]) continue;
    const Eigen::Vector3d x1((f1.un[i].x() - g.cx) / g.fx, (f1.un[i].y() - g.cy) / g.fy, 1.0);
    const Eigen::Vector3d line = E * x1;  // in kf2's normalised image
    const double line_norm = std::hypot(line.x(), line.y());
    if (line_norm < 1e-12) continue;
    ClosestTwo c;
    for (int j : cand2) {
      const int d = hamming(f1.descriptor(i), f2.descriptor(j));
      if (d >= c.second_dist) continue;  // cannot count: skip the epipolar test
      const Eigen::Vector3d x2((f2.un[j].x() - g.cx) / g.fx, (f2.un[j].y() - g.cy) / g.fy, 1.0);
      const double dist_px = std::abs(line.dot(x2)) / line_norm * g.fx;
      if (dist_px * dist_px > epipolar_chi2 * g.pyramid.sigma2[f2.level(j)]) continue;
      c.offer(j, d);
    }
    if (c.best < 0 || c.best_dist > max_distance || c.best_dist > ratio * c.second_dist) continue;
    if (c.best_dist < taken_dist[c.best]) {
      taken_dist[c.best] = c.best_dist;
      taken[c.best] = i;
    }
  }
  for (int j = 0; j < f2.size(); ++j)
    if (taken[j] >= 0) out.emplace_back(taken[j], j);
  return out;
}

}  // namespace bmp::tracker

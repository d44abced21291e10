#include "tracker/keypoint_tracks.hpp"

#include <limits>

#include "tracker/matcher.hpp"

namespace bmp::tracker {

std::vector<int> trackFromLastFrame(const Frame& frame, const Frame& last, const FrameGeometry& g,
                                    const std::vector<uint8_t>& open, const KeypointTrackOptions& options) {
  const Features& cur = *frame.features;
  const Features& prev = *last.features;
  std::vector<int> track(static_cast<std::size_t>(cur.size()), -1);
  std::vector<int> best_distance(static_cast<std::size_t>(cur.size()), std::numeric_limits<int>::max());
  const SE3 T_cur_last = frame.T_cam_world() * last.T_world_cam();
  for (int j = 0; j < prev.size(); ++j) {
    if (!prev.hasDepth(j) || prev.excluded[j]) continue;
    const Eigen::Vector3d p = T_cur_last * g.camera.backProject(prev.un[j], prev.depth[j]);
    if (p.z() <= 0.0) continue;
    const Eigen::Vector2d q = g.project(p);
    if (!g.inBounds(q.x(), q.y())) continue;
    const int level = prev.level(j);
    ClosestTwo c;
    for (int i : cur.inArea(g, q.x(), q.y(), options.radius_px, std::max(0, level - 1), level + 1))
      c.offer(i, hamming(prev.descriptor(j), cur.descriptor(i)));
    // The best must be clearly the best: a wide window holds many look-alikes.
    if (c.best < 0 || c.best_dist > options.max_distance || c.best_dist >= options.ratio * c.second_dist)
      continue;
    if (!open[c.best] || c.best_dist >= best_distance[c.best]) continue;
    best_distance[c.best] = c.best_dist;
    track[c.best] = j;
  }
  return track;
}

}  // namespace bmp::tracker

#include "tracker/keypoint_tracks.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "tracker/keypoint_window_grid.hpp"
#include "tracker/matcher.hpp"

namespace bmp::tracker {

std::vector<int> trackFromLastFrame(const Frame& frame, const Frame& last, const FrameGeometry& g,
                                    const std::vector<uint8_t>& open, const KeypointTrackOptions& options) {
  const Features& cur = *frame.features;
  const Features& prev = *last.features;
  std::vector<int> track(static_cast<std::size_t>(cur.size()), -1);
  std::vector<int> best_distance(static_cast<std::size_t>(cur.size()), std::numeric_limits<int>::max());
  const SE3 T_cur_last = frame.T_cam_world() * last.T_world_cam();
  // Every keypoint in the window is a candidate for the ratio test, but only an open one can take the
  // track. So the open ones are searched first: when none of them is close enough, the window's other
  // keypoints need no descriptor distance at all, and when one is, they are read only until one of them
  // is as close (a tie for the closest fails the ratio test, whichever comes first).
  std::vector<int> open_keys, closed_keys;
  for (int i = 0; i < cur.size(); ++i) (open[i] ? open_keys : closed_keys).push_back(i);
  const KeypointWindowGrid open_window(cur, g, options.radius_px, open_keys);
  const KeypointWindowGrid closed_window(cur, g, options.radius_px, closed_keys);
  for (int j = 0; j < prev.size(); ++j) {
    if (!prev.hasDepth(j) || prev.excluded[j]) continue;
    const Eigen::Vector3d p = T_cur_last * g.camera.backProject(prev.un[j], prev.depth[j]);
    if (p.z() <= 0.0) continue;
    const Eigen::Vector2d q = g.project(p);
    if (!g.inBounds(q.x(), q.y())) continue;
    const int level = prev.level(j);
    const uint8_t* d = prev.descriptor(j);
    ClosestTwo c;
    open_window.forEach(q.x(), q.y(), options.radius_px, level - 1, level + 1,
                        [&](int i) { c.offer(i, hamming(d, cur.descriptor(i))); });
    if (c.best < 0 || c.best_dist > options.max_distance || c.best_dist >= best_distance[c.best]) continue;
    // The best must be clearly the best: a wide window holds many look-alikes.
    int second = c.second_dist;
    closed_window.forEach(q.x(), q.y(), options.radius_px, level - 1, level + 1, [&](int i) {
      if (c.best_dist < options.ratio * second) second = std::min(second, hamming(d, cur.descriptor(i)));
    });
    if (c.best_dist >= options.ratio * second) continue;
    best_distance[c.best] = c.best_dist;
    track[c.best] = j;
  }
  return track;
}

}  // namespace bmp::tracker

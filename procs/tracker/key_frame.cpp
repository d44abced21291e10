#include "tracker/key_frame.hpp"

#include <algorithm>

namespace bmp::tracker {

KeyFrame::KeyFrame(int64_t i, const Frame& frame)
    : id(i),
      seq(frame.seq),
      stamp(frame.stamp),
      features(frame.features),
      points(frame.points),
      moving(frame.moving),
      dynamic(frame.dynamic),
      stand_in_z(frame.box_z_stand_in ? frame.box_z : std::vector<int8_t>{}),
      moved(frame.moved) {
  setPose(frame.T_world_cam());
  for (std::size_t k = 0; k < points.size(); ++k)
    if (points[k] && (frame.outlier[k] || points[k]->temporary() || points[k]->bad)) points[k].reset();
}

void KeyFrame::setPose(const SE3& T_world_cam) {
  T_world_cam_ = normalized(T_world_cam);
  T_cam_world_ = T_world_cam_.inverse();
}

std::vector<KeyFrame*> KeyFrame::bestCovisibles(int n) const {
  const std::size_t count =
      std::min<std::size_t>(best_covisible.size(), static_cast<std::size_t>(std::max(0, n)));
  return {best_covisible.begin(), best_covisible.begin() + static_cast<std::ptrdiff_t>(count)};
}

int KeyFrame::weight(KeyFrame* other) const {
  const auto it = connections.find(other);
  return it == connections.end() ? 0 : it->second;
}

void KeyFrame::sortConnections() {
  best_covisible.clear();
  for (const auto& [kf, w] : connections) best_covisible.push_back(kf);
  std::stable_sort(best_covisible.begin(), best_covisible.end(),
                   [this](KeyFrame* a, KeyFrame* b) { return connections.at(a) > connections.at(b); });
}

int KeyFrame::trackedPoints(int min_observations) const {
  int n = 0;
  for (const auto& mp : points)
    if (mp && !mp->bad && static_cast<int>(mp->observations.size()) >= min_observations) ++n;
  return n;
}

double KeyFrame::medianDepth() const {
  std::vector<double> depths;
  for (const auto& mp : points)
    if (mp && !mp->bad) depths.push_back((T_cam_world_ * mp->p_world).z());
  if (depths.empty()) return 1.0;
  std::nth_element(depths.begin(), depths.begin() + depths.size() / 2, depths.end());
  return depths[depths.size() / 2];
}

}  // namespace bmp::tracker

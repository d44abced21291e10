#include "tracker/map.hpp"

#include <algorithm>
#include <thread>

namespace bmp::tracker {

std::unique_lock<std::mutex> Map::lockForTracking() {
  tracking_waiting_.fetch_add(1);
  std::unique_lock<std::mutex> lock(mutex_);
  tracking_waiting_.fetch_sub(1);
  return lock;
}

void Map::yieldToTracking(std::unique_lock<std::mutex>& lock) {
  if (tracking_waiting_.load() == 0) return;
  lock.unlock();
  while (tracking_waiting_.load() > 0) std::this_thread::yield();
  lock.lock();
}

void Map::addKeyFrame(const std::shared_ptr<KeyFrame>& kf) {
  keyframes_[kf->id] = kf;
  keyframe_by_ptr_[kf.get()] = kf;
}

void Map::addPoint(const std::shared_ptr<MapPoint>& mp) {
  points_[mp.get()] = mp;
}

void Map::addObservation(KeyFrame* kf, int idx, const std::shared_ptr<MapPoint>& mp) {
  mp->observations[kf] = idx;
  kf->points[idx] = mp;
  if (mp->reference == nullptr) mp->reference = kf;
}

void Map::eraseObservation(KeyFrame* kf, const std::shared_ptr<MapPoint>& mp) {
  const auto it = mp->observations.find(kf);
  if (it == mp->observations.end()) return;
  if (kf->points[it->second] == mp) kf->points[it->second].reset();
  mp->observations.erase(it);
  if (mp->reference == kf)
    mp->reference = mp->observations.empty() ? nullptr : mp->observations.begin()->first;
  if (mp->observations.size() < 2) erasePoint(mp);
}

void Map::erasePoint(const std::shared_ptr<MapPoint>& mp) {
  if (mp->bad) return;
  mp->bad = true;
  for (const auto& [kf, idx] : mp->observations)
    if (kf->points[idx] == mp) kf->points[idx].reset();
  mp->observations.clear();
  mp->reference = nullptr;
  points_.erase(mp.get());
}

void Map::replacePoint(const std::shared_ptr<MapPoint>& from, const std::shared_ptr<MapPoint>& to) {
  if (from == to || from->bad || to->bad) return;
  const auto observations = from->observations;
  for (const auto& [kf, idx] : observations) {
    if (to->observations.count(kf) == 0) {
      kf->points[idx] = to;
      to->observations[kf] = idx;
    } else {
      kf->points[idx].reset();
    }
  }
  to->visible += from->visible;
  to->found += from->found;
  from->observations.clear();
  from->replaced_by = to;
  from->bad = true;
  from->reference = nullptr;
  points_.erase(from.get());
  to->updateDescriptor();
}

void Map::updateConnections(KeyFrame* kf, int min_weight) {
  std::map<KeyFrame*, int, KeyFrameIdLess> counts;
  for (const auto& mp : kf->points) {
    if (!mp || mp->bad) continue;
    for (const auto& [other, idx] : mp->observations) {
      (void)idx;
      if (other != kf) ++counts[other];
    }
  }
  // Drop old edges, then write the new ones on both sides.
  for (const auto& [other, w] : kf->connections) {
    (void)w;
    if (counts.count(other) == 0) {
      other->connections.erase(kf);
      other->sortConnections();
    }
  }
  kf->connections.clear();
  KeyFrame* best = nullptr;
  int best_weight = 0;
  for (const auto& [other, w] : counts) {
    if (w > best_weight) {
      best_weight = w;
      best = other;
    }
    if (w >= min_weight) kf->connections[other] = w;
  }
  if (kf->connections.empty() && best != nullptr) kf->connections[best] = best_weight;
  for (const auto& [other, w] : kf->connections) {
    other->connections[kf] = w;
    other->sortConnections();
  }
  kf->sortConnections();
  // The first connection fixes the spanning-tree parent: the strongest older keyframe.
  if (!kf->parent && !kf->best_covisible.empty()) {
    for (KeyFrame* candidate : kf->best_covisible) {
      if (candidate->id < kf->id && !candidate->bad) {
        kf->parent = keyFrame(candidate);
        candidate->children.insert(kf);
        break;
      }
    }
  }
}

void Map::eraseKeyFrame(const std::shared_ptr<KeyFrame>& kf, int min_weight) {
  if (kf->bad || !kf->parent) return;  // the first keyframe anchors the map
  // Every edge to it, including one-sided ones (updateConnections keeps the other side of an edge that fell
  // under min_weight): the keyframe is freed once culled, so no pointer to it may stay behind.
  for (const auto& [id, other] : keyframes_) {
    (void)id;
    if (other->connections.erase(kf.get()) > 0) other->sortConnections();
  }
  kf->connections.clear();
  kf->best_covisible.clear();
  for (std::size_t i = 0; i < kf->points.size(); ++i) {
    const auto mp = kf->points[i];
    if (mp) eraseObservation(kf.get(), mp);
  }
  // Children move to this keyframe's parent; their edges are refreshed so the graph stays connected.
  for (KeyFrame* child : kf->children) {
    child->parent = kf->parent;
    kf->parent->children.insert(child);
  }
  kf->children.clear();
  kf->parent->children.erase(kf.get());
  culled_[kf->id] = {kf->parent->id, kf->parent->T_cam_world() * kf->T_world_cam()};
  kf->bad = true;
  keyframes_.erase(kf->id);
  keyframe_by_ptr_.erase(kf.get());
  (void)min_weight;
}

SE3 Map::trajectoryPose(int64_t id) const {
  SE3 T_anchor_self = SE3::Identity();
  for (auto culled = culled_.find(id); culled != culled_.end(); culled = culled_.find(id)) {
    T_anchor_self = culled->second.T_parent_self * T_anchor_self;
    id = culled->second.parent_id;
  }
  return keyframes_.at(id)->T_world_cam() * T_anchor_self;
}

std::shared_ptr<KeyFrame> Map::keyFrame(const KeyFrame* kf) const {
  const auto it = keyframe_by_ptr_.find(kf);
  return it == keyframe_by_ptr_.end() ? nullptr : it->second;
}

std::shared_ptr<MapPoint> Map::point(const MapPoint* mp) const {
  const auto it = points_.find(mp);
  return it == points_.end() ? nullptr : it->second;
}

std::vector<std::shared_ptr<KeyFrame>> Map::keyFrames() const {
  std::vector<std::shared_ptr<KeyFrame>> out;
  out.reserve(keyframes_.size());
  for (const auto& [id, kf] : keyframes_) out.push_back(kf);
  return out;
}

std::vector<std::shared_ptr<MapPoint>> Map::points() const {
  std::vector<std::shared_ptr<MapPoint>> out;
  out.reserve(points_.size());
  for (const auto& [ptr, mp] : points_) out.push_back(mp);
  std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a->id < b->id; });
  return out;
}

}  // namespace bmp::tracker

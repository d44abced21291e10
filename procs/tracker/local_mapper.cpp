#include "tracker/local_mapper.hpp"

#include <algorithm>
#include <unordered_set>

#include "tracker/matcher.hpp"

namespace bmp::tracker {

LocalMapper::LocalMapper(Map& map, std::shared_ptr<const FrameGeometry> geometry, const TrackerConfig& config)
    : map_(map), geometry_(std::move(geometry)), config_(config), queue_(config.mapping.queue_capacity) {
  if (config_.mapping.threaded) thread_ = std::thread([this] { run(); });
}

LocalMapper::~LocalMapper() {
  finish();
}

bool LocalMapper::submit(std::shared_ptr<KeyFrame> kf) {
  return queue_.tryPush(std::move(kf));
}

void LocalMapper::processQueued() {
  while (auto kf = queue_.tryPop()) process(*kf);
}

std::vector<KeyFramePose> LocalMapper::takePoseUpdates() {
  std::lock_guard<std::mutex> lock(updates_mutex_);
  std::vector<KeyFramePose> out;
  out.swap(updates_);
  return out;
}

void LocalMapper::finish() {
  if (finished_) return;
  finished_ = true;
  queue_.close();
  if (thread_.joinable()) thread_.join();
  processQueued();
}

void LocalMapper::run() {
  while (auto kf = queue_.pop()) {
    busy_ = true;
    process(*kf);
    busy_ = false;
  }
}

void LocalMapper::process(const std::shared_ptr<KeyFrame>& kf) {
  Stopwatch watch;
  std::unique_lock<std::mutex> lock(map_.mutex());
  if (kf->bad) return;
  integrateKeyFrame(kf.get());
  cullRecentPoints(kf.get());
  // Between steps the lock is let go, so a frame being tracked waits for one step, not the whole keyframe.
  yieldLock(lock);
  triangulate(kf.get(), lock);
  yieldLock(lock);
  fuseWithNeighbours(kf.get(), lock);
  map_.updateConnections(kf.get(), config_.mapping.covisibility_min_weight);
  // Do not let a backlog wait behind BA: the next keyframe's links matter more to tracking.
  if (queue_.size() == 0) bundleAdjust(kf, lock);
  yieldLock(lock);
  cullKeyFrames(kf.get());
  timing_.add(watch.elapsedMs());
}

void LocalMapper::yieldLock(std::unique_lock<std::mutex>& lock) {
  map_.yieldToTracking(lock);
}

void LocalMapper::integrateKeyFrame(KeyFrame* kf) {
  const FrameGeometry& g = *geometry_;
  for (std::size_t i = 0; i < kf->points.size(); ++i) {
    auto mp = kf->points[i];
    while (mp && mp->bad && mp->replaced_by) mp = mp->replaced_by;
    if (!mp || mp->bad) {
      kf->points[i].reset();
      continue;
    }
    kf->points[i] = mp;
    const auto it = mp->observations.find(kf);
    if (it != mp->observations.end() && it->second == static_cast<int>(i)) {
      recent_points_.push_back(mp);  // made from this keyframe's depth by the tracker
      continue;
    }
    if (it != mp->observations.end()) {  // matched twice in one keyframe: keep the first
      kf->points[i].reset();
      continue;
    }
    map_.addObservation(kf, static_cast<int>(i), mp);
    mp->updateNormalAndDepth(g);
    mp->updateDescriptor();
  }
  map_.updateConnections(kf, config_.mapping.covisibility_min_weight);
}

void LocalMapper::cullRecentPoints(const KeyFrame* kf) {
  const auto& m = config_.mapping;
  std::vector<std::shared_ptr<MapPoint>> keep;
  keep.reserve(recent_points_.size());
  for (auto& mp : recent_points_) {
    if (mp->bad) continue;
    const int64_t age = kf->id - mp->first_kf_id;
    if (mp->foundRatio() < m.point_found_ratio ||
        (age >= 2 && static_cast<int>(mp->observations.size()) < m.point_min_observations)) {
      map_.erasePoint(mp);
    } else if (age < 3) {
      keep.push_back(mp);
    }
  }
  recent_points_.swap(keep);
}

void LocalMapper::fuseWithNeighbours(KeyFrame* kf, std::unique_lock<std::mutex>& lock) {
  const FrameGeometry& g = *geometry_;
  const double chi2 = config_.pose.chi2_rgbd;
  std::vector<KeyFrame*> targets;
  std::unordered_set<KeyFrame*> seen{kf};
  for (KeyFrame* nb : kf->bestCovisibles(config_.mapping.fuse_neighbors)) {
    if (nb->bad || !seen.insert(nb).second) continue;
    targets.push_back(nb);
    for (KeyFrame* nb2 : nb->bestCovisibles(5))
      if (!nb2->bad && seen.insert(nb2).second) targets.push_back(nb2);
  }
  // This keyframe's points into its neighbours ...
  // Only this thread culls keyframes or erases points, so the raw pointers survive the yields.
  for (KeyFrame* target : targets) {
    yieldLock(lock);
    if (target->bad) continue;
    std::vector<std::shared_ptr<MapPoint>> mine;
    for (const auto& mp : kf->points)
      if (mp && !mp->bad) mine.push_back(mp);
    fusePoints(map_, target, mine, g, config_.matcher, 3.0, chi2);
  }
  // ... and the neighbours' points into this keyframe.
  std::vector<std::shared_ptr<MapPoint>> theirs;
  std::unordered_set<const MapPoint*> added;
  for (KeyFrame* target : targets)
    for (const auto& mp : target->points)
      if (mp && !mp->bad && added.insert(mp.get()).second) theirs.push_back(mp);
  fusePoints(map_, kf, theirs, g, config_.matcher, 3.0, chi2);
  for (const auto& mp : kf->points) {
    if (!mp || mp->bad) continue;
    mp->updateDescriptor();
    mp->updateNormalAndDepth(g);
  }
}

void LocalMapper::cullKeyFrames(KeyFrame* kf) {
  const FrameGeometry& g = *geometry_;
  for (KeyFrame* candidate : kf->bestCovisibles(20)) {
    if (candidate->bad || !candidate->parent || candidate == kf) continue;
    int counted = 0, redundant = 0;
    for (std::size_t i = 0; i < candidate->points.size(); ++i) {
      const auto& mp = candidate->points[i];
      if (!mp || mp->bad) continue;
      const float d = candidate->features->depth[i];
      if (d <= 0.0f || d > g.close_depth) continue;  // only well-measured points count
      ++counted;
      if (mp->observations.size() <= 3) continue;
      const int level = candidate->features->level(static_cast<int>(i));
      int others = 0;
      for (const auto& [other, idx] : mp->observations) {
        if (other == candidate) continue;
        if (other->features->level(idx) <= level + 1 && ++others >= 3) break;
      }
      if (others >= 3) ++redundant;
    }
    if (counted > 0 && redundant > config_.mapping.keyframe_redundancy * counted) {
      const auto shared = map_.keyFrame(candidate);
      if (shared) map_.eraseKeyFrame(shared, config_.mapping.covisibility_min_weight);
    }
  }
}

}  // namespace bmp::tracker

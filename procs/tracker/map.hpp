#pragma once
// The map: keyframes and map points, the covisibility graph, and the ids. One mutex guards all of it:
// the tracker holds it from matching to the keyframe decision, local mapping holds it while it edits the
// map; neither holds it during feature extraction or a Ceres solve. Methods assume the caller holds it.
#include <atomic>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <unordered_map>
#include <vector>

#include "tracker/key_frame.hpp"
#include "tracker/map_point.hpp"

namespace bmp::tracker {

class Map {
 public:
  std::mutex& mutex() { return mutex_; }
  // Tracking has priority: it announces that it waits, and local mapping, at its yield points, lets go of the
  // lock until tracking has taken it (std::mutex is not fair: a plain unlock/lock would win it straight
  // back).
  std::unique_lock<std::mutex> lockForTracking();
  void yieldToTracking(std::unique_lock<std::mutex>& lock);

  int64_t newKeyFrameId() { return next_keyframe_id_++; }
  int64_t newPointId() { return next_point_id_++; }
  // Keyframes made so far: their ids are handed out in order from 0.
  int64_t keyFramesMade() const { return next_keyframe_id_; }

  void addKeyFrame(const std::shared_ptr<KeyFrame>& kf);
  void addPoint(const std::shared_ptr<MapPoint>& mp);
  // Records that keypoint idx of kf observes mp (both directions).
  void addObservation(KeyFrame* kf, int idx, const std::shared_ptr<MapPoint>& mp);
  // Removes the observation; a point left with fewer than two observations is erased.
  void eraseObservation(KeyFrame* kf, const std::shared_ptr<MapPoint>& mp);
  // Marks the point bad and detaches it from every keyframe.
  void erasePoint(const std::shared_ptr<MapPoint>& mp);
  // Moves every observation of `from` to `to` (fusion of duplicates).
  void replacePoint(const std::shared_ptr<MapPoint>& from, const std::shared_ptr<MapPoint>& to);
  // Recounts shared points and rewrites kf's covisibility edges (and the other side of each).
  void updateConnections(KeyFrame* kf, int min_weight);
  // Culls a keyframe: detaches its observations, edges and children, and keeps only its pose relative to
  // its parent (an anchor of a few bytes), so the keyframe and its features are freed once nothing else
  // holds them while the frames tracked against it keep their place in the trajectory.
  void eraseKeyFrame(const std::shared_ptr<KeyFrame>& kf, int min_weight);
  // The pose of keyframe `id`, live or culled (through its parent chain, so BA corrections count).
  SE3 trajectoryPose(int64_t id) const;

  std::shared_ptr<KeyFrame> keyFrame(const KeyFrame* kf) const;
  std::shared_ptr<MapPoint> point(const MapPoint* mp) const;
  std::vector<std::shared_ptr<KeyFrame>> keyFrames() const;  // by id
  std::size_t numKeyFrames() const { return keyframes_.size(); }
  std::size_t numPoints() const { return points_.size(); }
  std::vector<std::shared_ptr<MapPoint>> points() const;

 private:
  std::mutex mutex_;
  std::atomic<int> tracking_waiting_{0};
  int64_t next_keyframe_id_ = 0;
  int64_t next_point_id_ = 0;
  std::map<int64_t, std::shared_ptr<KeyFrame>> keyframes_;
  std::unordered_map<const MapPoint*, std::shared_ptr<MapPoint>> points_;
  std::unordered_map<const KeyFrame*, std::shared_ptr<KeyFrame>> keyframe_by_ptr_;
  struct CulledAnchor {
    int64_t parent_id;
    SE3 T_parent_self;
  };
  std::unordered_map<int64_t, CulledAnchor> culled_;
};

}  // namespace bmp::tracker

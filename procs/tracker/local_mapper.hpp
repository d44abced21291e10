#pragma once
// Local mapping: takes each new keyframe from a bounded queue and, holding the map lock only while it edits
// the map, links its observations, culls weak recent points, triangulates new points with its neighbours,
// fuses duplicates, runs local bundle adjustment (solve without the lock) and culls redundant keyframes.
// Runs in its own thread, or inline (processQueued) for deterministic runs.
#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "bmp/common/bounded_queue.hpp"
#include "bmp/common/se3.hpp"
#include "bmp/common/timing.hpp"
#include "tracker/key_frame.hpp"
#include "tracker/map.hpp"
#include "tracker/tracker_options.hpp"

namespace bmp::tracker {

struct KeyFramePose {
  int64_t id = 0;
  double stamp = 0.0;
  SE3 T_world_cam = SE3::Identity();
};

class LocalMapper {
 public:
  LocalMapper(Map& map, std::shared_ptr<const FrameGeometry> geometry, const TrackerConfig& config);
  ~LocalMapper();
  LocalMapper(const LocalMapper&) = delete;
  LocalMapper& operator=(const LocalMapper&) = delete;

  // False when the queue is full (the tracker then does not make the keyframe).
  bool submit(std::shared_ptr<KeyFrame> kf);
  bool acceptsKeyFrames() const { return !queue_.full(); }
  bool idle() const { return !busy_.load() && queue_.size() == 0; }
  // Inline mode: processes every queued keyframe now. The caller must not hold the map lock.
  void processQueued();
  // Keyframe poses moved by bundle adjustment since the last call.
  std::vector<KeyFramePose> takePoseUpdates();
  // Processes what is queued and stops the thread. Idempotent.
  void finish();
  const TimingStats& timing() const { return timing_; }

 private:
  void run();
  void process(const std::shared_ptr<KeyFrame>& kf);
  void integrateKeyFrame(KeyFrame* kf);
  void cullRecentPoints(const KeyFrame* kf);
  int triangulate(KeyFrame* kf, std::unique_lock<std::mutex>& lock);
  void yieldLock(std::unique_lock<std::mutex>& lock);
  void fuseWithNeighbours(KeyFrame* kf, std::unique_lock<std::mutex>& lock);
  void bundleAdjust(const std::shared_ptr<KeyFrame>& kf, std::unique_lock<std::mutex>& lock);
  void cullKeyFrames(KeyFrame* kf);

  Map& map_;
  std::shared_ptr<const FrameGeometry> geometry_;
  TrackerConfig config_;
  BoundedQueue<std::shared_ptr<KeyFrame>> queue_;
  std::vector<std::shared_ptr<MapPoint>> recent_points_;  // mapping thread only
  std::atomic<bool> busy_{false};
  std::mutex updates_mutex_;
  std::vector<KeyFramePose> updates_;
  TimingStats timing_;  // mapping thread only, read after finish()
  std::thread thread_;
  bool finished_ = false;
};

}  // namespace bmp::tracker

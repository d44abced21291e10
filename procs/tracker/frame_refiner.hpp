#pragma once
// The saved trajectory's second look at each frame. A frame's pose is estimated against the map as it stood
// at that moment; local BA then moves the keyframes and points it was tracked against. Like ORB-SLAM, the
// trajectory keeps each frame relative to its reference keyframe, so it follows that keyframe's corrections;
// here the frame is also re-estimated against its own inlier points once its keyframe has settled (left
// local BA), which takes out the error the frame had against the map of its moment. The live pose published
// per frame is untouched: this is the trajectory written at the end.
#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "bmp/common/se3.hpp"
#include "tracker/pose_optimizer.hpp"
#include "tracker/tracker_options.hpp"

namespace bmp::tracker {

class MapPoint;

// One pose inlier of a tracked frame. Weak: a frame waiting for its second look must not keep a culled point
// alive. Floats: about 40 bytes, kept for the frames of the last few keyframes only.
struct RefineObservation {
  std::weak_ptr<MapPoint> point;
  Eigen::Vector2f uv;        // undistorted pixel
  float u_right = -1.0f;     // u - bf / depth; negative: no depth
  float information = 1.0f;  // 1 / sigma^2 of the keypoint's level
  float weight = 1.0f;       // the weight it had in the frame's pose
};

// T_world_cam re-estimated against the observations' points as they stand now (those still good and not
// believed to move by now), or nothing when fewer than min_inliers of them agree. With a prior the position
// is also held to it (between its neighbours, betweenNeighbours()).
std::optional<SE3> refineFramePose(const SE3& T_world_cam, const std::vector<RefineObservation>& observations,
                                   const PoseCamera& camera, const PoseOptimizerOptions& options,
                                   double dynamic_threshold, int min_inliers,
                                   const PositionPrior* prior = nullptr);

// Where a frame at time t should be, given the frames before (t0, c0) and after (t1, c1) it: on the line
// between them at its time. By the second look both neighbours are known, so the prior is centred, not a
// prediction from the past as when the frame was tracked: an unknown acceleration a moves the camera off
// that line by a (t - t0)(t1 - t) / 2 at most. None when the times are not in order or accel is 0 (off).
std::optional<PositionPrior> betweenNeighbours(double t0, const Eigen::Vector3d& c0, double t, double t1,
                                               const Eigen::Vector3d& c1, double accel);

// The frames waiting for their second look, oldest first.
class FrameRefiner {
 public:
  struct Pending {
    std::size_t record = 0;      // the caller's index of the frame's trajectory record
    int64_t keyframes_made = 0;  // keyframes made before the frame
    std::vector<RefineObservation> observations;
  };

  explicit FrameRefiner(const RefineOptions& options) : options_(options) {}
  bool enabled() const { return options_.after_keyframes > 0; }
  void add(Pending frame);
  // Hands the frames due to refine(const Pending&), oldest first: those whose reference keyframe is
  // after_keyframes old, at most per_frame of them. Frames whose keyframe has not settled when the run ends
  // (all), or beyond max_pending (a camera that makes no keyframes), are let go with the pose they were
  // tracked with: local BA has not moved the map under them, so a second look has nothing to correct, and
  // it would lose the motion prior that held them (a camera at rest while a crowd passes: 1.6 -> 5.6 mm).
  template <typename Refine>
  void takeDue(int64_t keyframes_made, bool all, Refine&& refine) {
    int taken = 0;
    while (!pending_.empty()) {
      const bool settled = keyframes_made - pending_.front().keyframes_made >= options_.after_keyframes;
      const bool overflow = static_cast<int>(pending_.size()) > options_.max_pending;
      if (settled && (all || taken < options_.per_frame)) {
        refine(pending_.front());
        ++taken;
      } else if (!(overflow || (all && !settled))) {
        break;
      }
      pending_.pop_front();
    }
  }
  std::size_t pending() const { return pending_.size(); }

 private:
  RefineOptions options_;
  std::deque<Pending> pending_;
};

}  // namespace bmp::tracker

// The tracking steps of Tracker::track: motion model, reference keyframe, relocalisation, local map.
#include <algorithm>
#include <map>
#include <unordered_set>

#include "bmp/common/timing.hpp"
#include "tracker/frame_pose.hpp"
#include "tracker/matcher.hpp"
#include "tracker/relocalizer.hpp"
#include "tracker/temporary_points.hpp"
#include "tracker/tracker.hpp"

namespace bmp::tracker {

void Tracker::prepareLastFrame() {
  if (!last_frame_.features) return;
  for (auto& mp : last_frame_.points) {
    while (mp && mp->bad && mp->replaced_by) mp = mp->replaced_by;
    if (mp && (mp->bad || mp->temporary())) mp.reset();
  }
  if (reference_kf_) last_frame_.setPose(map_.trajectoryPose(reference_kf_->id) * last_T_ref_cam_);
  // Off by default: temporary points favour near (often moving) structure, and the map alone tracks better
  // in dynamic scenes.
  if (config_.tracking.temporal_points > 0)
    addTemporaryPoints(last_frame_, *geometry_, config_.tracking.temporal_points);
}

void Tracker::optimizePose(Frame& frame, double* position_std_m) {
  {
    const ScopedAccumulator timer(dynamic_ms_);
    dynamic_.applyPriors(frame);
  }
  optimizeFramePose(frame, *geometry_, config_.pose, position_prior_ ? &*position_prior_ : nullptr,
                    position_std_m);
}

namespace {

// The constant-velocity motion over dt, from one measured over velocity_dt: a dropped frame in between
// must not leave the prediction a frame behind. Rotation by its angle-axis, translation linearly (the
// motions between frames are small); beyond max_scale frames' worth the model says nothing.
std::optional<SE3> scaledMotion(const SE3& velocity, double velocity_dt, double dt, double max_scale) {
  if (velocity_dt <= 0.0 || dt <= 0.0) return velocity;
  const double s = dt / velocity_dt;
  if (s > max_scale) return std::nullopt;
  const Eigen::AngleAxisd aa(velocity.rotation());
  SE3 out = SE3::Identity();
  out.linear() = Eigen::AngleAxisd(aa.angle() * s, aa.axis()).toRotationMatrix();
  out.translation() = velocity.translation() * s;
  return out;
}

}  // namespace

bool Tracker::trackWithMotionModel(Frame& frame) {
  if (!velocity_ || !last_frame_.features) return false;
  const auto& o = config_.tracking;
  const std::optional<SE3> motion =
      scaledMotion(*velocity_, velocity_dt_, frame.stamp - last_frame_.stamp, o.motion_max_scale);
  if (!motion) return false;
  frame.setPose(last_frame_.T_world_cam() * *motion);
  position_prior_ = motion_prior_.predict(last_frame_.center(), frame.stamp - last_frame_.stamp);
  int matches = matchFromLastFrame(frame, last_frame_, *geometry_, o, o.motion_search_radius);
  if (matches < o.min_matches_motion) {
    frame.clearMatches();
    matches = matchFromLastFrame(frame, last_frame_, *geometry_, o, 2.0 * o.motion_search_radius);
  }
  if (matches < o.min_matches_motion) {
    frame.clearMatches();
    position_prior_.reset();
    return false;
  }
  optimizePose(frame);
  const bool ok = dropOutliers(frame) >= o.min_inliers_motion;
  if (!ok) {
    frame.clearMatches();
    position_prior_.reset();  // the motion model failed: what tracks the frame next is not held to it
  }
  return ok;
}

// After a gap (frames dropped by a tracker that fell behind) the constant-velocity guess can be far off in a
// fast turn and still keep a few matches, enough to pass: a wrong pose that the local map then follows and a
// keyframe makes permanent. So when it keeps under recheck_inlier_ratio of the last frame's tracked points,
// the reference keyframe's descriptor matches, which need no guess, are tried too. If they keep more inliers,
// their pose is the guess the motion model lacked: the last frame's points are searched again around it
// (descriptor matches alone are fewer and less precise), and the better of the two is kept.
bool Tracker::trackFromLastFrame(Frame& frame, TrackResult& result) {
  GapRecheck& recheck = result.gap_recheck;
  if (!trackWithMotionModel(frame)) {
    result.pose_source = PoseSource::kReferenceKeyFrame;
    return trackReferenceKeyFrame(frame);
  }
  result.pose_source = PoseSource::kMotionModel;
  const auto& o = config_.tracking;
  // Off, or no gap: nothing to count (every frame passes here).
  if (o.recheck_inlier_ratio <= 0.0 || frame.stamp - last_frame_.stamp <= o.recheck_gap_s) return true;
  const int inliers = countTracked(frame);
  if (inliers >= o.recheck_inlier_ratio * countTracked(last_frame_)) return true;
  recheck = GapRecheck::kMotionKept;
  Frame from_reference = frame;
  if (!trackReferenceKeyFrame(from_reference) || countTracked(from_reference) <= inliers) return true;
  frame = std::move(from_reference);
  recheck = GapRecheck::kReferenceTaken;
  result.pose_source = PoseSource::kReferenceKeyFrame;
  Frame guessed = frame;
  guessed.clearMatches();
  if (matchFromLastFrame(guessed, last_frame_, *geometry_, o, o.motion_search_radius) < o.min_matches_motion)
    return true;
  optimizePose(guessed);
  dropOutliers(guessed);
  if (countTracked(guessed) > countTracked(frame)) frame = std::move(guessed);
  return true;
}

bool Tracker::trackReferenceKeyFrame(Frame& frame) {
  if (!reference_kf_) return false;
  const auto& o = config_.tracking;
  std::vector<std::shared_ptr<MapPoint>> points;
  for (const auto& mp : reference_kf_->points)
    if (mp && !mp->bad) points.push_back(mp);
  frame.clearMatches();
  std::vector<std::shared_ptr<MapPoint>> matches(frame.features->size());
  if (matchByDescriptors(*frame.features, points, o.descriptor_match_ratio, o.match_threshold_high, matches) <
      15)
    return false;
  frame.points = matches;
  frame.setPose(last_frame_.T_world_cam());
  optimizePose(frame);
  const bool ok = dropOutliers(frame) >= o.min_inliers_motion;
  if (!ok) frame.clearMatches();
  return ok;
}

bool Tracker::applyLateBoxes(int64_t seq, const std::vector<ObjectBox>& boxes) {
  if (!dynamic_.enabled()) return false;
  const auto lock = map_.lockForTracking();
  const auto kfs = map_.keyFrames();
  for (auto it = kfs.rbegin(); it != kfs.rend(); ++it) {
    if ((*it)->seq < seq) break;  // ids grow with seq: nothing older can match
    if ((*it)->seq != seq) continue;
    dynamic_.observeLate(**it, boxes);
    return true;
  }
  return false;
}

bool Tracker::applyLateBoxesToKeyFrame(int64_t id, const std::vector<ObjectBox>& boxes) {
  if (!dynamic_.enabled()) return false;
  const auto lock = map_.lockForTracking();
  for (const auto& kf : map_.keyFrames())
    if (kf->id == id) {
      dynamic_.observeLate(*kf, boxes);
      return true;
    }
  return false;
}

cv::Mat Tracker::keyframeMask(int64_t id, const std::vector<ObjectBox>* boxes, const cv::Mat& depth) {
  const auto lock = map_.lockForTracking();
  for (const auto& kf : map_.keyFrames())
    if (kf->id == id)
      return dynamic_.mask(*kf->features, *geometry_, kf->dynamic, boxes,
                           boxes ? dynamic_.lateMovingShare(*kf, *boxes) : std::vector<float>{}, depth,
                           geometry_->camera.intrinsics().depth_scale);
  return {};
}

bool Tracker::relocalise(Frame& frame) {
  auto kf = relocalize(frame, map_, *geometry_, config_, dynamic_);
  if (!kf) return false;
  reference_kf_ = kf;
  return true;
}

void Tracker::updateLocalMap(const Frame& frame) {
  // Keyframes that see the frame's points, ranked by how many; then their best covisibles, parents, children.
  std::map<KeyFrame*, int, KeyFrameIdLess> counts;
  for (std::size_t i = 0; i < frame.points.size(); ++i) {
    const auto& mp = frame.points[i];
    if (!mp || frame.outlier[i] || mp->bad) continue;
    for (const auto& [kf, idx] : mp->observations) {
      (void)idx;
      ++counts[kf];
    }
  }
  std::vector<std::pair<int, KeyFrame*>> ranked;
  for (const auto& [kf, n] : counts)
    if (!kf->bad) ranked.emplace_back(n, kf);
  std::stable_sort(ranked.begin(), ranked.end(),
                   [](const auto& a, const auto& b) { return a.first > b.first; });
  if (!ranked.empty()) reference_kf_ = map_.keyFrame(ranked.front().second);
  if (!reference_kf_ || reference_kf_->bad) {
    auto kfs = map_.keyFrames();
    reference_kf_ = kfs.empty() ? nullptr : kfs.back();
  }
  const std::size_t cap = static_cast<std::size_t>(config_.tracking.max_local_keyframes);
  std::vector<KeyFrame*> local;
  std::unordered_set<KeyFrame*> in_local;
  auto add = [&](KeyFrame* kf) {
    if (kf && !kf->bad && local.size() < cap && in_local.insert(kf).second) local.push_back(kf);
  };
  for (const auto& [n, kf] : ranked) add(kf);
  const std::size_t first_ring = local.size();
  for (std::size_t i = 0; i < first_ring && local.size() < cap; ++i) {
    for (KeyFrame* nb : local[i]->bestCovisibles(10)) add(nb);
    for (KeyFrame* child : local[i]->children) add(child);
    add(local[i]->parent.get());
  }
  if (local.empty() && reference_kf_) add(reference_kf_.get());
  local_keyframes_.clear();
  local_points_.clear();
  std::unordered_set<const MapPoint*> seen;
  for (KeyFrame* kf : local) {
    local_keyframes_.push_back(map_.keyFrame(kf));
    for (const auto& mp : kf->points)
      if (mp && !mp->bad && seen.insert(mp.get()).second) local_points_.push_back(mp);
  }
}

bool Tracker::trackLocalMap(Frame& frame) {
  const auto& o = config_.tracking;
  updateLocalMap(frame);
  const bool after_reloc = frame.seq - last_reloc_seq_ < 2 || state_ == TrackingState::kLost;
  // Points already matched (from the last frame) were in view too: counted visible as the local map's are,
  // or their found/visible ratio would look better than it is and culling would spare them.
  for (const auto& mp : frame.points)
    if (mp && !mp->bad && !mp->temporary()) ++mp->visible;
  matchLocalPoints(frame, local_points_, *geometry_, o, config_.matcher,
                   after_reloc ? o.reloc_search_radius : o.local_search_radius);
  optimizePose(frame, &frame.position_std_m);  // the frame's last solve: the one its pose comes from
  // The geometric observation; the map points take the posteriors only if the frame tracks (below).
  {
    const ScopedAccumulator timer(dynamic_ms_);
    dynamic_.conclude(frame, *geometry_, last_frame_.features ? &last_frame_ : nullptr);
  }
  int inliers = 0;
  for (std::size_t i = 0; i < frame.points.size(); ++i) {
    const auto& mp = frame.points[i];
    if (!mp || frame.outlier[i] || mp->bad || frame.isDynamic(i)) continue;
    if (!mp->observations.empty()) {
      ++mp->found;
      ++inliers;
    }
  }
  const bool recently_relocalised = frame.seq - last_reloc_seq_ < config_.keyframes.max_frames;
  const bool tracked =
      inliers >= (recently_relocalised || state_ == TrackingState::kLost ? o.min_inliers_after_reloc
                                                                         : o.min_inliers_local_map);
  // A frame that fails here was posed wrongly: every residual looks like motion, and its posteriors would
  // mark the map's static points as moving (left out of local BA and of the relocalisation that follows).
  // Committed before the outliers are dropped: an outlier's large residual is the geometric observation.
  if (tracked) dynamic_.commit(frame);
  dropOutliers(frame);
  // Temporary points helped the pose; they must not be mistaken for map points from here on.
  for (auto& mp : frame.points)
    if (mp && mp->temporary()) mp.reset();
  return tracked;
}

}  // namespace bmp::tracker

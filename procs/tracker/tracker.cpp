#include "tracker/tracker.hpp"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

#include "bmp/common/timing.hpp"
#include "tracker/trajectory_smoother.hpp"

namespace bmp::tracker {

const char* toString(TrackingState state) {
  switch (state) {
    case TrackingState::kInitialising:
      return "INITIALISING";
    case TrackingState::kOk:
      return "OK";
    case TrackingState::kLost:
      return "LOST";
    case TrackingState::kRelocalised:
      return "RELOCALISED";
  }
  return "?";
}

const char* toString(GapRecheck recheck) {
  switch (recheck) {
    case GapRecheck::kNone:
      return "none";
    case GapRecheck::kMotionKept:
      return "motion_kept";
    case GapRecheck::kReferenceTaken:
      return "reference_taken";
  }
  return "?";
}

const char* toString(PoseSource source) {
  switch (source) {
    case PoseSource::kNone:
      return "none";
    case PoseSource::kMapStart:
      return "map_start";
    case PoseSource::kMotionModel:
      return "motion";
    case PoseSource::kReferenceKeyFrame:
      return "reference";
    case PoseSource::kRelocalisation:
      return "relocalisation";
  }
  return "?";
}

Tracker::Tracker(const CameraIntrinsics& camera, const TrackerConfig& config)
    : config_(config),
      geometry_(std::make_shared<const FrameGeometry>(camera, config)),
      extractor_(config.orb),
      dynamic_(config.dynamic, config.pose),
      held_boxes_(config.dynamic.mode == DynamicMode::kNone ? 0.0 : config.dynamic.held_box_s,
                  config.dynamic.held_box_iou),
      mapper_(std::make_unique<LocalMapper>(map_, geometry_, config)),
      motion_prior_(config.pose),
      refiner_(config.refine) {}

Tracker::~Tracker() {
  finish();
}

void Tracker::finish() {
  mapper_->finish();
}

TrackResult Tracker::track(const TrackerInput& input) {
  Stopwatch watch;
  TrackResult result;
  // The frame's boxes, with the persons the detector found just before and missed now.
  const std::optional<std::vector<ObjectBox>> boxes =
      input.boxes_stand_in ? input.boxes : held_boxes_.complete(input.boxes, input.stamp);
  Frame frame = makeFrame(input, boxes, result);  // ORB, undistortion, depth, exclusion: no map lock needed
  dynamic_ms_ = 0.0;
  position_prior_.reset();
  {
    const ScopedAccumulator timer(dynamic_ms_);
    dynamic_.observe(frame, boxes ? &*boxes : nullptr, last_frame_.features ? &last_frame_ : nullptr);
  }
  {
    Stopwatch wait;
    const auto lock = map_.lockForTracking();
    result.lock_wait_ms = wait.elapsedMs();
    result.keyframe_updates = mapper_->takePoseUpdates();
    bool tracked = false;
    if (state_ == TrackingState::kInitialising) {
      tracked = initialise(frame, result);
      result.pose_source = PoseSource::kMapStart;
    } else {
      prepareLastFrame();  // follow BA corrections and fusions; temporary depth points for the motion model
      if (last_frame_.features) result.since_last_s = frame.stamp - last_frame_.stamp;
      bool first = false;
      if (state_ == TrackingState::kLost) {
        result.pose_source = PoseSource::kRelocalisation;
        first = relocalise(frame);
      } else {
        first = trackFromLastFrame(frame, result);
      }
      if (first) result.first_inliers = countTracked(frame);
      tracked = first && trackLocalMap(frame);
      if (tracked && state_ == TrackingState::kLost) last_reloc_seq_ = frame.seq;
      if (tracked) {
        state_ = last_reloc_seq_ == frame.seq ? TrackingState::kRelocalised : TrackingState::kOk;
        followMotion(frame);
        // Before a new keyframe adds its points: the pose's own inliers.
        result.keypoint_in_pose.resize(frame.points.size());
        for (std::size_t i = 0; i < frame.points.size(); ++i) result.keypoint_in_pose[i] = inPose(frame, i);
        result.num_tracked = static_cast<int>(
            std::count(result.keypoint_in_pose.begin(), result.keypoint_in_pose.end(), uint8_t{1}));
        result.position_std_m = frame.position_std_m;
        if (needNewKeyFrame(frame)) insertKeyFrame(frame, result);
      } else {
        state_ = TrackingState::kLost;
        forgetMotion();
      }
    }
    if (tracked) rememberFrame(frame);
    if (!tracked) result.pose_source = PoseSource::kNone;  // its first inliers stay: why it was lost
    result.state = state_;
    result.T_world_cam = frame.T_world_cam();
    result.num_map_points = static_cast<int>(map_.numPoints());
    result.num_keyframes = static_cast<int>(map_.numKeyFrames());
    result.reference_keyframe_id = reference_kf_ ? reference_kf_->id : -1;
    result.num_dynamic = frame.numDynamic();
    result.keypoint_dynamic = frame.dynamic;
    result.keypoint_in_region.assign(frame.box_z.begin(), frame.box_z.end());
    if (result.keypoint_in_pose.empty()) result.keypoint_in_pose.assign(frame.points.size(), 0);
    result.keypoints.reserve(frame.features->keys.size());
    for (const auto& k : frame.features->keys) result.keypoints.push_back(k.pt);
    if (result.new_keyframe) {
      const ScopedAccumulator timer(dynamic_ms_);
      result.dynamic_mask =
          dynamic_.mask(*frame.features, *geometry_, frame.dynamic, boxes ? &*boxes : nullptr,
                        frame.box_moving_share, input.depth, geometry_->camera.intrinsics().depth_scale);
    }
    result.dynamic_ms = dynamic_ms_;
  }
  if (!config_.mapping.threaded) mapper_->processQueued();
  result.processing_ms = watch.elapsedMs();
  return result;
}

void Tracker::followMotion(const Frame& frame) {
  // After relocalisation the last frame is from before the loss: no velocity from it.
  if (state_ != TrackingState::kOk) return forgetMotion();
  velocity_ = last_frame_.T_cam_world() * frame.T_world_cam();
  velocity_dt_ = frame.stamp - last_frame_.stamp;
  motion_prior_.observe(last_frame_.center(), velocity_dt_,
                        {frame.stamp, frame.center(), frame.position_std_m, false});
}

Frame Tracker::makeFrame(const TrackerInput& input, const std::optional<std::vector<ObjectBox>>& boxes,
                         TrackResult& result) const {
  Stopwatch watch;
  cv::Mat gray;
  if (input.image.channels() == 3)
    cv::cvtColor(input.image, gray, cv::COLOR_BGR2GRAY);
  else
    gray = input.image;
  auto features = buildFeatures(extractor_.extract(gray, sparseRegions(boxes)), input.depth, *geometry_,
                                input.keypoint_weight, input.exclusion_mask);
  result.stamp = input.stamp;
  result.seq = input.seq;
  result.num_keypoints = features->size();
  result.num_excluded = features->numExcluded();
  result.extract_ms = watch.elapsedMs();
  Frame frame(input.seq, input.stamp, std::move(features));
  frame.box_z_stand_in = input.boxes_stand_in;
  return frame;
}

SparseRegions Tracker::sparseRegions(const std::optional<std::vector<ObjectBox>>& boxes) const {
  const DynamicOptions& d = config_.dynamic;
  SparseRegions sparse;
  if (!boxes || d.box_keypoint_share >= 1.0 || d.mode == DynamicMode::kNone) return sparse;
  sparse.share = d.box_keypoint_share;
  for (const ObjectBox& b : *boxes)
    if (b.level == DynamicLevel::kHigh) sparse.boxes.push_back(b.box);
  return sparse;
}

bool Tracker::initialise(Frame& frame, TrackResult& result) {
  const Features& f = *frame.features;
  int with_depth = 0;
  for (int i = 0; i < f.size(); ++i) with_depth += f.hasDepth(i) && !f.excluded[i];
  if (with_depth < config_.tracking.init_min_keypoints) return false;
  frame.setPose(SE3::Identity());
  {
    const ScopedAccumulator timer(dynamic_ms_);
    dynamic_.applyPriors(frame);  // nothing matched yet: the boxes alone decide
  }
  auto kf = std::make_shared<KeyFrame>(map_.newKeyFrameId(), frame);
  map_.addKeyFrame(kf);
  for (int i = 0; i < f.size(); ++i) {
    if (!f.hasDepth(i) || f.excluded[i] || frame.isDynamic(i)) continue;
    auto mp = std::make_shared<MapPoint>(
        map_.newPointId(), geometry_->camera.backProject(f.un[i], f.depth[i]), f.descriptors.row(i), kf->id);
    mp->initGeometry(kf->center(), f.level(i), *geometry_);
    mp->moving_probability = frame.moving[i];
    map_.addPoint(mp);
    map_.addObservation(kf.get(), i, mp);
    frame.points[i] = mp;
  }
  mapper_->submit(kf);
  reference_kf_ = kf;
  last_keyframe_seq_ = frame.seq;
  state_ = TrackingState::kOk;
  result.new_keyframe = KeyFramePose{kf->id, kf->stamp, kf->T_world_cam()};
  result.num_tracked = 0;
  return true;
}

bool Tracker::needNewKeyFrame(const Frame& frame) const {
  const auto& k = config_.keyframes;
  if (!mapper_->acceptsKeyFrames()) return false;
  const int num_kfs = static_cast<int>(map_.numKeyFrames());
  if (frame.seq - last_reloc_seq_ < k.max_frames && num_kfs > k.max_frames) return false;
  const int ref_matches = reference_kf_->trackedPoints(num_kfs <= 2 ? 1 : 2);
  const Features& f = *frame.features;
  int tracked_close = 0, untracked_close = 0;
  for (int i = 0; i < f.size(); ++i) {
    // A mover's keypoints are neither tracked nor missing structure: they do not call for a keyframe.
    if (!f.hasDepth(i) || f.depth[i] > geometry_->close_depth || f.excluded[i] || frame.isDynamic(i))
      continue;
    const auto& mp = frame.points[i];
    if (mp && !frame.outlier[i] && !mp->observations.empty())
      ++tracked_close;
    else
      ++untracked_close;
  }
  const int64_t since = frame.seq - last_keyframe_seq_;
  const bool need_close = tracked_close < k.close_tracked_max && untracked_close > k.close_untracked_min &&
                          since >= k.close_min_frames;
  const int inliers = countTracked(frame);
  const double ratio = num_kfs < 2 ? 0.4 : k.ref_ratio;
  const bool c1a = since >= k.max_frames;
  const bool c1b = since >= k.min_frames && mapper_->idle();
  const bool c1c = inliers < 0.25 * ref_matches || need_close;
  const bool c2 = (inliers < ratio * ref_matches || need_close) && inliers > 15;
  if (!((c1a || c1b || c1c) && c2)) return false;
  if (inliers >= k.still_min_inliers && atRestOnReference(frame)) return false;
  return !(inliers >= k.revisit_min_inliers && placeIsMapped(frame));
}

bool Tracker::atRestOnReference(const Frame& frame) const {
  const auto& k = config_.keyframes;
  if (k.still_distance_m <= 0.0 || !reference_kf_) return false;
  const SE3 moved = reference_kf_->T_world_cam().inverse() * frame.T_world_cam();
  return moved.translation().norm() < k.still_distance_m &&
         Eigen::AngleAxisd(moved.linear()).angle() < k.still_angle_deg * M_PI / 180.0;
}

bool Tracker::placeIsMapped(const Frame& frame) const {
  const auto& k = config_.keyframes;
  const Eigen::Vector3d center = frame.T_world_cam().translation();
  const Eigen::Vector3d axis = frame.T_world_cam().linear().col(2);
  const double min_cos = std::cos(k.revisit_angle_deg * M_PI / 180.0);
  for (const auto& kf : local_keyframes_) {
    if (kf->bad || frame.stamp - kf->stamp < k.revisit_min_age_s) continue;
    if ((kf->center() - center).norm() < k.revisit_distance_m &&
        kf->T_world_cam().linear().col(2).dot(axis) > min_cos)
      return true;
  }
  return false;
}

void Tracker::insertKeyFrame(Frame& frame, TrackResult& result) {
  auto kf = std::make_shared<KeyFrame>(map_.newKeyFrameId(), frame);
  map_.addKeyFrame(kf);
  // Points from depth: every close keypoint without one, and the nearest others up to new_points_min.
  const Features& f = *frame.features;
  int count = 0;
  for (int i : f.nearestWithDepth()) {
    if (f.depth[i] > geometry_->close_depth && count >= config_.keyframes.new_points_min) break;
    if (frame.isDynamic(i)) continue;
    ++count;
    if (kf->points[i]) continue;
    const Eigen::Vector3d p = frame.T_world_cam() * geometry_->camera.backProject(f.un[i], f.depth[i]);
    auto mp = std::make_shared<MapPoint>(map_.newPointId(), p, f.descriptors.row(i), kf->id);
    mp->initGeometry(kf->center(), f.level(i), *geometry_);
    mp->moving_probability = frame.moving[i];
    map_.addPoint(mp);
    map_.addObservation(kf.get(), i, mp);
    frame.points[i] = mp;
    frame.outlier[i] = 0;
  }
  mapper_->submit(kf);
  reference_kf_ = kf;
  last_keyframe_seq_ = frame.seq;
  result.new_keyframe = KeyFramePose{kf->id, kf->stamp, kf->T_world_cam()};
}

bool Tracker::inPose(const Frame& frame, std::size_t i) const {
  const auto& mp = frame.points[i];
  return mp && !frame.outlier[i] && !mp->bad && !mp->observations.empty() && !frame.isDynamic(i);
}

int Tracker::countTracked(const Frame& frame) const {
  int n = 0;
  for (std::size_t i = 0; i < frame.points.size(); ++i) n += inPose(frame, i);
  return n;
}

Tracker::FrameRecord::FrameRecord(double stamp_s, int64_t reference, const SE3& T, float std_m)
    : stamp(stamp_s),
      reference_id(reference),
      t_ref_cam(T.translation().cast<float>()),
      position_std_m(std_m),
      q_ref_cam(Eigen::Quaterniond(T.linear()).cast<float>()) {}

SE3 Tracker::FrameRecord::T_ref_cam() const {
  return makeSE3(t_ref_cam.cast<double>(), q_ref_cam.cast<double>());
}

void Tracker::rememberFrame(const Frame& frame) {
  last_T_ref_cam_ = reference_kf_->T_cam_world() * frame.T_world_cam();
  if (state_ == TrackingState::kRelocalised) relocalised_records_.push_back(records_.size());
  records_.emplace_back(frame.stamp, reference_kf_->id, last_T_ref_cam_,
                        static_cast<float>(frame.position_std_m));
  last_frame_ = frame;
  // A keyframe's own pose is refined by local BA itself.
  if (refiner_.enabled() && last_keyframe_seq_ != frame.seq) {
    FrameRefiner::Pending pending{records_.size() - 1, map_.keyFramesMade(), {}};
    const Features& f = *frame.features;
    const FrameGeometry& g = *geometry_;
    for (int i = 0; i < f.size(); ++i) {
      if (!inPose(frame, static_cast<std::size_t>(i))) continue;
      pending.observations.push_back({frame.points[i], f.un[i].cast<float>(),
                                      static_cast<float>(f.uRight(g, i)),
                                      static_cast<float>(g.pyramid.inv_sigma2[f.level(i)]), f.weight[i]});
    }
    refiner_.add(std::move(pending));
  }
  refineSettledFrames(false);
}

void Tracker::refineSettledFrames(bool all) {
  const FrameGeometry& g = *geometry_;
  const PoseCamera camera{g.fx, g.fy, g.cx, g.cy, g.bf};
  refiner_.takeDue(map_.keyFramesMade(), all, [&](const FrameRefiner::Pending& p) {
    FrameRecord& r = records_[p.record];
    const SE3 T_world_ref = map_.trajectoryPose(r.reference_id);
    // The frames before and after it, as they stand now (the one before has had its second look).
    std::optional<PositionPrior> prior;
    if (p.record > 0 && p.record + 1 < records_.size()) {
      const FrameRecord& before = records_[p.record - 1];
      const FrameRecord& after = records_[p.record + 1];
      prior = betweenNeighbours(before.stamp, recordPose(before).translation(), r.stamp, after.stamp,
                                recordPose(after).translation(), config_.pose.motion_prior_accel);
    }
    const std::optional<SE3> refined =
        refineFramePose(T_world_ref * r.T_ref_cam(), p.observations, camera, config_.pose,
                        config_.dynamic.threshold, config_.refine.min_inliers, prior ? &*prior : nullptr);
    if (refined) r = FrameRecord(r.stamp, r.reference_id, T_world_ref.inverse() * *refined, r.position_std_m);
  });
}

SE3 Tracker::recordPose(const FrameRecord& r) const {
  return map_.trajectoryPose(r.reference_id) * r.T_ref_cam();
}

Trajectory Tracker::trajectory() {
  std::lock_guard<std::mutex> lock(map_.mutex());
  refineSettledFrames(true);
  Trajectory out;
  out.reserve(records_.size());
  std::vector<SmootherSample> samples;
  samples.reserve(records_.size());
  for (const auto& r : records_) {
    out.push_back({r.stamp, normalized(recordPose(r))});
    samples.push_back({r.stamp, out.back().T_world_cam.translation(), r.position_std_m, false});
  }
  for (const std::size_t i : relocalised_records_) samples[i].starts_stretch = true;
  const std::vector<Eigen::Vector3d> smoothed = smoothPositions(samples, config_.refine.smoother);
  for (std::size_t i = 0; i < out.size(); ++i) out[i].T_world_cam.translation() = smoothed[i];
  return out;
}

Trajectory Tracker::keyFrameTrajectory() {
  std::lock_guard<std::mutex> lock(map_.mutex());
  Trajectory out;
  for (const auto& kf : map_.keyFrames()) out.push_back({kf->stamp, kf->T_world_cam()});
  return out;
}

}  // namespace bmp::tracker

#include "tracker/lcm/tracker_node.hpp"

#include <algorithm>
#include <stdexcept>

#include "bmp/common/log.hpp"
#include "bmp/common/stamp.hpp"
#include "bmp/lcm/conversions.hpp"
#include "detector/lcm/detections_message.hpp"
#include "tracker/lcm/tracker_messages.hpp"
#include "tracker/stand_in_boxes.hpp"

namespace bmp::tracker {

namespace {
const char* const kLiveComment = "live poses as tracked; a clean exit replaces them with the optimised ones";
}  // namespace

TrackerNode::TrackerNode(ProcessContext& ctx, TrackerConfig config, TrackerChannels channels,
                         std::size_t queue_capacity, const TrackerOutputs& outputs, DetectionPolicy policy)
    : ctx_(ctx),
      config_(config),
      channels_(std::move(channels)),
      queue_(queue_capacity, WhenFull::kDropOldest),
      policy_(policy),
      outputs_(outputs) {
  // Reproducible runs map inline: the keyframe decision and BA no longer depend on thread timing.
  if (policy_.reproducible) config_.mapping.threaded = false;
  if (config_.dynamic.mode != DynamicMode::kNone)
    ctx_.lcm.subscribe<detections_t>(
        channels_.detections, [this](const detections_t& msg, const ReceivedInfo&) { onDetections(msg); });
  if (!outputs_.trajectory.empty()) live_trajectory_.emplace(outputs_.trajectory, kLiveComment);
  if (!outputs_.keyframe_trajectory.empty())
    live_keyframes_.emplace(outputs_.keyframe_trajectory, kLiveComment);
  if (!outputs_.frame_log.empty()) frame_log_.emplace(outputs_.frame_log);
  ctx_.lcm.subscribe<rgbd_frame_t>(channels_.frames,
                                   [this](const rgbd_frame_t& msg, const ReceivedInfo&) { onFrame(msg); });
  receiver_ = std::thread([this] { receive(); });
}

TrackerNode::~TrackerNode() {
  receiving_ = false;
  queue_.close();
  if (receiver_.joinable()) receiver_.join();
}

void TrackerNode::receive() {
  while (receiving_ && !ctx_.stop.requested()) {
    if (!ctx_.lcm.handle(100)) {
      log::error("LCM receive failed; stopping");
      ctx_.stop.request();
    }
  }
}

void TrackerNode::onFrame(const rgbd_frame_t& msg) {
  // Judged here, in arrival order, before the queue: a frame the queue later drops was received and is
  // counted as dropped, not also as a gap (lost) when the next one is tracked.
  const FrameStream::Verdict verdict = stream_.accept(msg);
  if (verdict.repeat) return last_pose_.answerRepeat(ctx_.lcm, channels_.pose, msg.seq, msg.utime);
  ++received_;  // a repeat is not a frame of its own
  lost_before_ += verdict.lost_before;
  if (!verdict.ok) return refuse(msg, verdict);
  newest_frame_seq_ = msg.seq;  // accepted: in order, or a restarted stream (lower seq) followed from here
  book_.frameHeard(msg.seq, msg.utime);
  queue_.push({msg, verdict});
}

void TrackerNode::refuse(const rgbd_frame_t& msg, const FrameStream::Verdict& verdict) {
  // Answered here, on the receive thread: a flood of bad frames never pushes real ones out of the queue.
  const std::string reason = "frame seq " + std::to_string(msg.seq) + ": " + verdict.reason;
  if (const auto left_out = warnings_.admit("refused frames")) {
    if (verdict.lost_before > 0)
      log::warn(verdict.lost_before, " frame(s) before seq ", msg.seq, " never arrived");
    log::warn(reason, "; skipped", leftOutNote(*left_out));
  }
  // Not remembered for a resend: the frame sent again is judged again and answered again, and a refused
  // frame (another publisher's) must not replace the answer a lockstep resend of the real one repeats.
  // A damaged copy of a frame taken is not answered: its answer would go out under the real frame's name.
  if (!verdict.copies_accepted) {
    ctx_.lcm.publish(channels_.pose, toSkippedPoseMessage(msg, reason));
    ++refusals_answered_;
  }
  {
    const std::lock_guard<std::mutex> lock(refusal_mutex_);
    last_refusal_ = reason;
  }
  ++refused_;  // counted in the heartbeat as malformed (and the answer as published) by syncStatus
}

void TrackerNode::onDetections(const detections_t& msg) {
  // Checked as the contract says (levels, classes, boxes inside the image); a bad one throws and is
  // counted as malformed by the LCM node.
  const detector::FrameDetections d = detector::fromDetectionsMessage(msg);
  // Boxes in another image's pixels would cut the wrong regions. A skipped answer has no boxes and no
  // image size (the detector could not read the frame).
  if (const camera_t* camera = stream_.camera();
      camera != nullptr && d.skipped.empty() && (d.width != camera->width || d.height != camera->height))
    throw std::runtime_error("answer for frame " + std::to_string(d.seq) + " is for a " +
                             std::to_string(d.width) + "x" + std::to_string(d.height) +
                             " image, the camera's is " + std::to_string(camera->width) + "x" +
                             std::to_string(camera->height));
  // The book keeps the answers with the highest seq: ones far ahead of every frame heard (forged, or from
  // another run) would push out the real ones waiting for their frames. An answer comes after its frame
  // unless that frame was lost on its way here; kAnswersAhead allows for a second of such frames.
  if (d.seq > newest_frame_seq_ + kAnswersAhead)
    throw std::runtime_error("answer for frame " + std::to_string(d.seq) +
                             ", far ahead of the newest frame " + std::to_string(newest_frame_seq_));
  FrameBoxes boxes;
  boxes.utime = d.utime;
  boxes.usable = d.skipped.empty();
  boxes.boxes = toObjectBoxes(d.detections);
  if (std::string why = book_.add(d.seq, std::move(boxes)); !why.empty()) throw std::runtime_error(why);
  ++detections_heard_;  // only an answer taken: a refused stray one must not turn lockstep's wait back on
}

TrackerNode::FrameBoxChoice TrackerNode::boxesFor(const rgbd_frame_t& msg) {
  if (config_.dynamic.mode == DynamicMode::kNone) return {};
  // Without any detector on the bus, waiting would only slow every frame: wait again once one is heard.
  const bool wait = policy_.reproducible && (detections_heard_ > 0 || !warned_no_detections_);
  const auto wait_ms = std::chrono::milliseconds(wait ? static_cast<int64_t>(policy_.wait_ms) : 0);
  std::optional<FrameBoxes> got = book_.take(msg.seq, msg.utime, wait_ms);
  if (!got && wait && detections_heard_ == 0 && !warned_no_detections_) {
    warned_no_detections_ = true;
    log::warn("no answer on ", channels_.detections, " within ", policy_.wait_ms,
              " ms: tracking without boxes until the detector is heard");
  }
  if (got && got->usable) return {std::move(got->boxes), true};
  if (got || wait) return {};  // the detector skipped it, or lockstep: no stand-in
  // Real time, the answer not here yet: the newest answer before it stands in, moved on for its age.
  std::optional<std::vector<ObjectBox>> stand_in =
      standInBoxes(book_.newestBefore(msg.seq, msg.seq - static_cast<int64_t>(book_.capacity()), 2),
                   msg.utime, config_.dynamic);
  if (!stand_in) return {};
  ++stale_boxes_used_;
  return {std::move(stand_in), false};
}

void TrackerNode::releaseHeldKeyframes(bool all) {
  if (!camera_settled_ && !all) return;
  while (!held_.empty()) {
    HeldKeyframe& h = held_.front();
    // One held only for the camera to settle has its boxes (or, in lockstep, took the frame's answer).
    std::optional<FrameBoxes> late;
    if (h.awaits_boxes) late = book_.take(h.frame.seq, h.frame.utime, std::chrono::milliseconds(0));
    const bool waiting = h.awaits_boxes && !late && h.held.elapsedMs() < policy_.keyframe_hold_ms;
    if (waiting && !all) break;  // in order: the rest wait too
    if (late && late->usable) {
      late_applied_ += tracker_->applyLateBoxesToKeyFrame(h.keyframe.id, late->boxes);
      const cv::Mat mask = tracker_->keyframeMask(h.keyframe.id, &late->boxes, h.depth);
      if (!mask.empty()) h.mask = mask;
    }
    ctx_.lcm.publish(channels_.keyframe, toKeyFrameMessage(h.frame, h.color, h.depth, h.keyframe, h.mask));
    ctx_.status.published();
    held_.pop_front();
  }
}

void TrackerNode::syncStatus() {
  const int64_t received = received_.load();
  const auto dropped = static_cast<int64_t>(queue_.dropped());
  const int64_t lost = lost_before_.load();
  ctx_.status.received(received - received_reported_);
  ctx_.status.dropped(dropped - dropped_reported_);
  ctx_.status.lost(lost - lost_reported_);
  received_reported_ = received;
  dropped_reported_ = dropped;
  lost_reported_ = lost;
  const int64_t answered = refusals_answered_.load();
  ctx_.status.published(answered - answered_reported_);
  answered_reported_ = answered;
  const int64_t refused = refused_.load();
  if (refused != refused_reported_) {
    ctx_.status.malformed(refused - refused_reported_);
    refused_reported_ = refused;
    const std::lock_guard<std::mutex> lock(refusal_mutex_);
    ctx_.status.setMessage(last_refusal_);
  }
}

void TrackerNode::run(double idle_exit_s) {
  Stopwatch idle;  // since a frame last arrived (taken or refused: a stream of refused frames is no idle)
  int64_t received_before = 0;
  while (!ctx_.stop.requested()) {
    std::optional<Queued> msg = queue_.popFor(std::chrono::milliseconds(held_.empty() ? 100 : 10));
    syncStatus();
    if (tracker_) releaseHeldKeyframes(false);
    if (const int64_t received = received_.load(); msg || received != received_before) {
      received_before = received;
      idle.restart();
    }
    if (msg) {
      process(*msg);
    } else if (idle_exit_s > 0 && received_before > 0 && idle.elapsedMs() > idle_exit_s * 1000.0) {
      log::info("no frame for ", idle_exit_s, " s: finishing");
      break;
    }
    ctx_.status.tick();
  }
  // Keyframes of a camera that never settled stay unsent, as during the run: they may be a forged frame's.
  if (tracker_ && camera_settled_) releaseHeldKeyframes(true);
  if (!held_.empty() && !camera_settled_)
    log::info(held_.size(), " keyframe(s) of a camera that never settled not sent to the mapper");
  receiving_ = false;
  if (receiver_.joinable()) receiver_.join();  // its counts are final from here
  syncStatus();
  // Received but still queued when the stop came: counted as dropped, so every frame received is accounted
  // for (tracked, dropped, or refused).
  const std::size_t unfinished = queue_.size();
  ctx_.status.dropped(static_cast<int64_t>(unfinished));
  if (tracker_) tracker_->finish();
  if (stale_boxes_used_ + late_applied_ > 0)
    log::info("boxes: ", stale_boxes_used_,
              " frame(s) observed with an earlier frame's (their own not come), ", late_applied_,
              " keyframe(s) took theirs late");
  log::info("tracked ", timing_.count(), " frames, ", lost_, " lost, ", degraded_, " degraded (fewer than ",
            policy_.degraded_inliers, " inliers); ", lost_before_.load(), " frame(s) never arrived, ",
            queue_.dropped(), " dropped while busy, ", unfinished, " still queued at exit, ", refused_.load(),
            " refused, ", stream_.repeats(), " resent by capture (", last_pose_.answeredAgain(),
            " answered again); tracking ", timing_.summary());
}

void TrackerNode::skip(const rgbd_frame_t& msg, const std::string& reason) {
  ctx_.status.malformed();
  ctx_.status.setMessage(reason);
  if (const auto left_out = warnings_.admit("unreadable frames"))
    log::warn(reason, "; skipped", leftOutNote(*left_out));
  const slam_pose_t answer = toSkippedPoseMessage(msg, reason);
  last_pose_.remember(answer);
  ctx_.lcm.publish(channels_.pose, answer);  // answered all the same
  ctx_.status.published();
}

void TrackerNode::startAgainForNewCamera() {
  if (!tracker_) return;
  log::warn("dropping the map of ", tracker_->keyFrameTrajectory().size(), " keyframe(s) (", held_.size(),
            " not yet sent to the mapper) made with the replaced camera; tracking starts again");
  held_.clear();
  tracker_.reset();  // made again from this frame's camera
  // The live files hold that map's poses: a planner reading them must not take them for the new camera's.
  if (live_trajectory_) live_trajectory_->restart();
  if (live_keyframes_) live_keyframes_->restart();
}

void TrackerNode::process(const Queued& frame) {
  const rgbd_frame_t& msg = frame.msg;
  const FrameStream::Verdict& verdict = frame.verdict;
  if (!verdict.reason.empty()) log::warn("frame seq ", msg.seq, ": ", verdict.reason);  // e.g. resynchronised
  if (tracker_ && !map_camera_.holds(msg.camera, msg.depth_scale)) startAgainForNewCamera();
  camera_settled_ = verdict.camera_settled;
  if (verdict.lost_before > 0)
    log::warn(verdict.lost_before, " frame(s) before seq ", msg.seq, " never arrived");
  // Frames missed just before this one, for the frame log: lost upstream (this frame's own gap: the running
  // count also held gaps of frames received after it) or dropped from our queue (older than this one, as the
  // queue drops its oldest). Never below 0: a jump found to be another publisher's gives its gap back. The
  // tracker scales its constant-velocity prediction over the time since the last frame (up to 4 periods),
  // so the velocity is kept across a gap: forgetting it sent every frame after a gap to the reference
  // keyframe's descriptor matches, which keep fewer inliers than the scaled prediction.
  const auto dropped = static_cast<int64_t>(queue_.dropped());
  const int64_t missed = std::max<int64_t>(0, verdict.lost_before) + dropped - dropped_seen_;
  dropped_seen_ = dropped;
  cv::Mat color, depth;
  try {
    color = decodeImage(fromMsg(msg.color));
    depth = decodeImage(fromMsg(msg.depth));
    if (depth.type() != CV_16UC1 || depth.size() != color.size())
      throw ImageError("depth is not 16-bit at colour size");
  } catch (const std::exception& e) {  // ImageError, or the allocation of a decoded image
    return skip(msg, "frame seq " + std::to_string(msg.seq) + ": " + e.what());
  }
  if (!tracker_) {
    const CameraIntrinsics camera = fromMsg(msg.camera, msg.depth_scale);
    tracker_ = std::make_unique<Tracker>(camera, config_);
    map_camera_.pin(msg.camera, msg.depth_scale);
    log::info("camera ", camera.width, "x", camera.height, " fx ", camera.fx, " from ", msg.source);
  }
  TrackerInput input;
  input.stamp = utimeToSeconds(msg.utime);
  input.seq = msg.seq;
  input.image = color;
  input.depth = depth;
  FrameBoxChoice choice = boxesFor(msg);
  input.boxes = std::move(choice.boxes);
  input.boxes_stand_in = input.boxes && !choice.own;
  const TrackResult r = tracker_->track(input);
  timing_.add(r.processing_ms);
  lost_ += r.state == TrackingState::kLost;
  if (frame_log_) logFrame(r, missed, choice);  // before the answer: whoever heard it finds its line
  publish(msg, r, color, depth, choice.own);
  ctx_.status.processed();
}

void TrackerNode::logFrame(const TrackResult& r, int64_t missed, const FrameBoxChoice& choice) {
  const char* boxes = config_.dynamic.mode == DynamicMode::kNone ? "-"
                      : choice.own                               ? "own"
                      : choice.boxes                             ? "stale"
                                                                 : "none";
  try {
    frame_log_->append(r, {static_cast<int>(missed), boxes});
  } catch (const FrameLogError& e) {  // a full disk stops the log, not the tracking
    log::error(e.what(), "; the frame log stops here");
    frame_log_.reset();
  }
}

void TrackerNode::publish(const rgbd_frame_t& msg, const TrackResult& r, const cv::Mat& color,
                          const cv::Mat& depth, bool had_boxes) {
  // On disk before it is announced: whoever saw the pose finds it in the file even if we are killed now.
  if (live_trajectory_ && r.ok()) live_trajectory_->append({r.stamp, r.T_world_cam});
  if (live_keyframes_ && r.new_keyframe)
    live_keyframes_->append({r.new_keyframe->stamp, r.new_keyframe->T_world_cam});
  slam_pose_t pose = toPoseMessage(msg, r);
  // Tracked, but on few inliers: a real-time run under load shows it before its pose goes wrong, so the
  // consumer is told not to trust this one fully. The frame that starts the map (its first keyframe) is the
  // origin by definition, not an estimate, and has no inliers to count.
  const bool starts_map = r.new_keyframe && r.new_keyframe->id == 0;
  if (pose.state == slam_pose_t::STATE_OK && !starts_map && r.num_tracked < policy_.degraded_inliers) {
    pose.state = slam_pose_t::STATE_DEGRADED;
    ++degraded_;
  }
  last_pose_.remember(pose);
  ctx_.lcm.publish(channels_.pose, pose);
  ctx_.status.published();
  if (r.new_keyframe) {
    const cv::Mat mask = r.dynamic_mask.empty() ? cv::Mat::zeros(color.size(), CV_8UC1) : r.dynamic_mask;
    const bool awaits_boxes =
        !had_boxes && config_.dynamic.mode != DynamicMode::kNone && !policy_.reproducible;
    // Keyframes go out in id order, so one made while others are held waits behind them: the mapper takes
    // keyframe 0 arriving after keyframe 1 as a new map.
    if (awaits_boxes || !camera_settled_ || !held_.empty()) {
      held_.push_back({msg, color, depth, *r.new_keyframe, mask, awaits_boxes, Stopwatch()});
    } else {
      ctx_.lcm.publish(channels_.keyframe, toKeyFrameMessage(msg, color, depth, *r.new_keyframe, mask));
      ctx_.status.published();
    }
  }
  // A keyframe still held for its boxes has not been announced: its new pose goes into the held message
  // instead, so the mapper never hears of a keyframe's move before the keyframe.
  std::vector<KeyFramePose> updates;
  for (const KeyFramePose& u : r.keyframe_updates) {
    const auto held = std::find_if(held_.begin(), held_.end(),
                                   [&](const HeldKeyframe& h) { return h.keyframe.id == u.id; });
    if (held != held_.end())
      held->keyframe.T_world_cam = u.T_world_cam;
    else
      updates.push_back(u);
  }
  if (!updates.empty()) {
    ctx_.lcm.publish(channels_.keyframe_poses, toKeyFramePosesMessage(msg.utime, updates));
    ctx_.status.published();
  }
}

void TrackerNode::writeTrajectories() {
  if (!tracker_) {
    log::warn("no frame received; the trajectory files hold no pose");
    return;
  }
  live_trajectory_.reset();
  live_keyframes_.reset();
  if (!outputs_.trajectory.empty()) {
    const Trajectory t = tracker_->trajectory();
    writeTumTrajectory(outputs_.trajectory, t);
    log::info("trajectory (", t.size(), " poses) written to ", outputs_.trajectory);
  }
  if (!outputs_.keyframe_trajectory.empty()) {
    const Trajectory t = tracker_->keyFrameTrajectory();
    writeTumTrajectory(outputs_.keyframe_trajectory, t);
    log::info("keyframe trajectory (", t.size(), " poses) written to ", outputs_.keyframe_trajectory);
  }
}

}  // namespace bmp::tracker

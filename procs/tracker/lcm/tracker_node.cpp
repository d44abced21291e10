#include "tracker/lcm/tracker_node.hpp"

#include "bmp/common/log.hpp"
#include "bmp/lcm/conversions.hpp"
#include "tracker/lcm/tracker_messages.hpp"

namespace bmp::tracker {

namespace {
const char* const kLiveComment = "live poses as tracked; a clean exit replaces them with the optimised ones";
}  // namespace

TrackerNode::TrackerNode(ProcessContext& ctx, TrackerConfig config, TrackerChannels channels,
                         std::size_t queue_capacity, const TrackerOutputs& outputs)
    : ctx_(ctx),
      config_(std::move(config)),
      channels_(std::move(channels)),
      capacity_(queue_capacity),
      outputs_(outputs) {
  if (!outputs_.trajectory.empty()) live_trajectory_.emplace(outputs_.trajectory, kLiveComment);
  if (!outputs_.keyframe_trajectory.empty())
    live_keyframes_.emplace(outputs_.keyframe_trajectory, kLiveComment);
  ctx_.lcm.subscribe<rgbd_frame_t>(channels_.frames, [this](const rgbd_frame_t& msg, const ReceivedInfo&) {
    ctx_.status.received();
    if (pending_.size() >= capacity_) {  // bounded: the oldest waiting frame gives way
      pending_.pop_front();
      ctx_.status.dropped();
    }
    pending_.push_back(msg);
  });
}

void TrackerNode::run(double idle_exit_s) {
  Stopwatch idle;
  while (!ctx_.stop.requested()) {
    ctx_.lcm.handle(pending_.empty() ? 100 : 0);
    if (!pending_.empty()) {
      const rgbd_frame_t msg = std::move(pending_.front());
      pending_.pop_front();
      process(msg);
      idle.restart();
    } else if (idle_exit_s > 0 && tracker_ && idle.elapsedMs() > idle_exit_s * 1000.0) {
      log::info("no frame for ", idle_exit_s, " s: finishing");
      break;
    }
    ctx_.status.tick();
  }
  if (tracker_) tracker_->finish();
  log::info("tracked ", timing_.count(), " frames, ", lost_, " lost; tracking ", timing_.summary());
}

void TrackerNode::process(const rgbd_frame_t& msg) {
  cv::Mat color, depth;
  try {
    color = decodeImage(fromMsg(msg.color));
    depth = decodeImage(fromMsg(msg.depth));
    if (depth.type() != CV_16UC1 || depth.size() != color.size())
      throw ImageError("depth is not 16-bit at colour size");
  } catch (const ImageError& e) {
    ctx_.status.malformed();
    ctx_.status.setMessage(std::string("frame ") + std::to_string(msg.seq) + ": " + e.what());
    log::warn("frame ", msg.seq, ": ", e.what(), "; skipped");
    ctx_.lcm.publish(channels_.pose, toSkippedPoseMessage(msg));  // answered all the same
    ctx_.status.published();
    return;
  }
  if (!tracker_) {
    const CameraIntrinsics camera = fromMsg(msg.camera, msg.depth_scale);
    tracker_ = std::make_unique<Tracker>(camera, config_);
    log::info("camera ", camera.width, "x", camera.height, " fx ", camera.fx, " from ", msg.source);
  }
  TrackerInput input;
  input.stamp = static_cast<double>(msg.utime) * 1e-6;
  input.seq = msg.seq;
  input.image = color;
  input.depth = depth;
  const TrackResult r = tracker_->track(input);
  timing_.add(r.processing_ms);
  lost_ += r.state == TrackingState::kLost;

  // On disk before it is announced: whoever saw the pose finds it in the file even if we are killed now.
  if (live_trajectory_ && r.ok()) live_trajectory_->append({r.stamp, r.T_world_cam});
  if (live_keyframes_ && r.new_keyframe)
    live_keyframes_->append({r.new_keyframe->stamp, r.new_keyframe->T_world_cam});
  ctx_.lcm.publish(channels_.pose, toPoseMessage(msg, r));
  ctx_.status.published();
  if (r.new_keyframe) {
    if (empty_mask_.size() != color.size()) empty_mask_ = cv::Mat::zeros(color.size(), CV_8UC1);
    ctx_.lcm.publish(channels_.keyframe, toKeyFrameMessage(msg, color, depth, *r.new_keyframe, empty_mask_));
    ctx_.status.published();
  }
  if (!r.keyframe_updates.empty()) {
    ctx_.lcm.publish(channels_.keyframe_poses, toKeyFramePosesMessage(msg.utime, r.keyframe_updates));
    ctx_.status.published();
  }
  ctx_.status.processed();
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

// bmp-tracker: RGBD_FRAME in; SLAM_POSE (every frame), SLAM_KEYFRAME and SLAM_KEYFRAME_POSES out. The
// algorithm is bmp::tracker::Tracker; this file only turns messages into calls and results into messages.
#include <cstdio>
#include <deque>
#include <memory>
#include <optional>

#include <bmp/keyframe_poses_t.hpp>
#include <bmp/keyframe_t.hpp>
#include <bmp/rgbd_frame_t.hpp>
#include <bmp/slam_pose_t.hpp>

#include "bmp/common/log.hpp"
#include "bmp/common/timing.hpp"
#include "bmp/lcm/conversions.hpp"
#include "bmp/lcm/process.hpp"
#include "tracker/tracker.hpp"
#include "tracker/tracker_config.hpp"

namespace {

using namespace bmp;
using namespace bmp::tracker;

struct Channels {
  std::string frames = "RGBD_FRAME";
  std::string pose = "SLAM_POSE";
  std::string keyframe = "SLAM_KEYFRAME";
  std::string keyframe_poses = "SLAM_KEYFRAME_POSES";
};

void addOptions(ArgParser& args) {
  args.addOption("trajectory", "FILE", "write every tracked frame's pose on exit (TUM format)");
  args.addOption("keyframe-trajectory", "FILE", "write the keyframe poses on exit (TUM format)");
  args.addOption("idle-exit", "SECONDS",
                 "exit once no frame arrived for this long after the first (0: never)", "0");
  args.addEpilog(
      "Subscribes RGBD_FRAME; publishes SLAM_POSE for every frame, SLAM_KEYFRAME for each new keyframe\n"
      "(colour, depth, all-zero dynamic mask) and SLAM_KEYFRAME_POSES after local bundle adjustment.\n"
      "Example:\n"
      "  bmp-tracker --trajectory out/trajectory.txt --keyframe-trajectory out/keyframes.txt\n");
}

// A message's image as it travels, re-encoded only when it arrived raw.
image_t forwardOrEncode(const image_t& msg, const cv::Mat& decoded, ImageEncoding encoding) {
  if (msg.encoding != static_cast<int8_t>(ImageEncoding::kRaw)) return msg;
  return toMsg(encodeImage(decoded, encoding));
}

class TrackerNode {
 public:
  TrackerNode(ProcessContext& ctx, TrackerConfig config, Channels channels, std::size_t queue_capacity)
      : ctx_(ctx), config_(std::move(config)), channels_(std::move(channels)), capacity_(queue_capacity) {
    ctx_.lcm.subscribe<rgbd_frame_t>(channels_.frames, [this](const rgbd_frame_t& msg, const ReceivedInfo&) {
      ctx_.status.received();
      if (pending_.size() >= capacity_) {  // bounded: the oldest waiting frame gives way
        pending_.pop_front();
        ctx_.status.dropped();
      }
      pending_.push_back(msg);
    });
  }

  void run(double idle_exit_s) {
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

  Tracker* tracker() { return tracker_.get(); }

 private:
  void process(const rgbd_frame_t& msg) {
    cv::Mat color, depth;
    try {
      color = decodeImage(fromMsg(msg.color));
      depth = decodeImage(fromMsg(msg.depth));
      if (depth.type() != CV_16UC1 || depth.size() != color.size())
        throw ImageError("depth is not 16-bit at colour size");
    } catch (const ImageError& e) {
      ctx_.status.malformed();
      ctx_.status.setMessage(std::string("frame ") + std::to_string(msg.seq) + ": " + e.what());
      log::warn("frame ", msg.seq, ": ", e.what());
      return;
    }
    if (!tracker_) {
      camera_ = fromMsg(msg.camera, msg.depth_scale);
      camera_msg_ = msg.camera;
      tracker_ = std::make_unique<Tracker>(camera_, config_);
      log::info("camera ", camera_.width, "x", camera_.height, " fx ", camera_.fx, " from ", msg.source);
    }
    TrackerInput input;
    input.stamp = static_cast<double>(msg.utime) * 1e-6;
    input.seq = msg.seq;
    input.image = color;
    input.depth = depth;
    const TrackResult r = tracker_->track(input);
    timing_.add(r.processing_ms);
    lost_ += r.state == TrackingState::kLost;
    publishPose(msg, r);
    if (r.new_keyframe) publishKeyFrame(msg, color, depth, *r.new_keyframe);
    if (!r.keyframe_updates.empty()) publishKeyFramePoses(msg.utime, r.keyframe_updates);
    ctx_.status.processed();
  }

  void publishPose(const rgbd_frame_t& msg, const TrackResult& r) {
    slam_pose_t out;
    out.utime = msg.utime;
    out.seq = msg.seq;
    out.T_world_cam = toMsg(r.T_world_cam);
    out.state = static_cast<int8_t>(r.state);
    out.num_keypoints = r.num_keypoints;
    out.num_tracked = r.num_tracked;
    out.num_dynamic = r.num_excluded;
    out.num_map_points = r.num_map_points;
    out.reference_keyframe_id = r.reference_keyframe_id;
    out.processing_ms = static_cast<float>(r.processing_ms);
    ctx_.lcm.publish(channels_.pose, out);
    ctx_.status.published();
  }

  void publishKeyFrame(const rgbd_frame_t& msg, const cv::Mat& color, const cv::Mat& depth,
                       const KeyFramePose& kf) {
    keyframe_t out;
    out.utime = msg.utime;
    out.id = kf.id;
    out.seq = msg.seq;
    out.T_world_cam = toMsg(kf.T_world_cam);
    out.camera = camera_msg_;
    out.depth_scale = msg.depth_scale;
    out.color = forwardOrEncode(msg.color, color, ImageEncoding::kJpeg);
    out.depth = forwardOrEncode(msg.depth, depth, ImageEncoding::kPng);
    if (empty_mask_.data.empty() || empty_mask_.width != color.cols || empty_mask_.height != color.rows)
      empty_mask_ = toMsg(encodeImage(cv::Mat::zeros(color.size(), CV_8UC1), ImageEncoding::kPng));
    out.dynamic_mask = empty_mask_;  // no dynamic handling yet: nothing is masked
    ctx_.lcm.publish(channels_.keyframe, out);
    ctx_.status.published();
  }

  void publishKeyFramePoses(int64_t utime, const std::vector<KeyFramePose>& updates) {
    keyframe_poses_t out;
    out.utime = utime;
    out.num_keyframes = static_cast<int32_t>(updates.size());
    for (const auto& u : updates) {
      out.ids.push_back(u.id);
      out.T_world_cam.push_back(toMsg(u.T_world_cam));
    }
    ctx_.lcm.publish(channels_.keyframe_poses, out);
    ctx_.status.published();
  }

  ProcessContext& ctx_;
  TrackerConfig config_;
  Channels channels_;
  std::size_t capacity_;
  std::deque<rgbd_frame_t> pending_;
  std::unique_ptr<Tracker> tracker_;
  CameraIntrinsics camera_;
  camera_t camera_msg_{};
  image_t empty_mask_{};
  TimingStats timing_;
  int64_t lost_ = 0;
};

int run(ProcessContext& ctx) {
  const TrackerConfig config = trackerConfigFromConfig(ctx.config.section("tracker"));
  const Config process = ctx.config.section("process");
  Channels channels;
  channels.frames = process.get<std::string>("frames_channel", channels.frames);
  channels.pose = process.get<std::string>("pose_channel", channels.pose);
  channels.keyframe = process.get<std::string>("keyframe_channel", channels.keyframe);
  channels.keyframe_poses = process.get<std::string>("keyframe_poses_channel", channels.keyframe_poses);
  const int capacity = process.get<int>("frame_queue_capacity", 4);
  if (capacity < 1) throw ConfigError(process.origin() + ": process.frame_queue_capacity must be at least 1");
  finishConfig(ctx);

  TrackerNode node(ctx, config, channels, static_cast<std::size_t>(capacity));
  ctx.status.tick(true);
  node.run(ctx.args.number("idle-exit"));
  // Written on every exit path that reaches here, SIGINT included: the loop only ends by a stop request.
  if (node.tracker()) {
    if (ctx.args.given("trajectory")) {
      const Trajectory t = node.tracker()->trajectory();
      writeTumTrajectory(ctx.args.value("trajectory"), t);
      log::info("trajectory (", t.size(), " poses) written to ", ctx.args.value("trajectory"));
    }
    if (ctx.args.given("keyframe-trajectory")) {
      const Trajectory t = node.tracker()->keyFrameTrajectory();
      writeTumTrajectory(ctx.args.value("keyframe-trajectory"), t);
      log::info("keyframe trajectory (", t.size(), " poses) written to ",
                ctx.args.value("keyframe-trajectory"));
    }
  } else {
    log::warn("no frame received; no trajectory written");
  }
  ctx.status.finish();
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return bmp::runProcess(argc, argv,
                         {"bmp-tracker",
                          "ORB-SLAM-style RGB-D tracking and local mapping: subscribes RGBD_FRAME, publishes "
                          "SLAM_POSE for every frame, SLAM_KEYFRAME and SLAM_KEYFRAME_POSES.",
                          "tracker.yaml", addOptions, run});
}

#include "tracker/tracker_settings.hpp"

#include "tracker/tracker_config.hpp"

namespace bmp::tracker {

void addTrackerOptions(ArgParser& args) {
  args.addOption("trajectory", "FILE",
                 "every tracked frame's pose (TUM format): written as tracked, replaced by the optimised "
                 "trajectory on exit");
  args.addOption("keyframe-trajectory", "FILE", "the keyframe poses (TUM format), likewise");
  args.addOption(
      "frame-log", "FILE",
      "one tab-separated line per frame tracked (not for a frame skipped or refused): state, inliers of the "
      "first pose and after the local map, where the first pose came from, frames missed before it, boxes "
      "own/stale/none, times");
  args.addOption("frame-policy", "every|latest",
                 "every: reproducible (wait for each frame's boxes, map inline; lockstep runs); latest: real "
                 "time, never wait",
                 "latest");
  args.addOption("dynamic-mode", "MODE", "override tracker.dynamic.mode: none|boxes|paper|depth|geometric");
  args.addOption("idle-exit", "SECONDS",
                 "exit once no frame arrived for this long after the first received (0: never)", "0");
  args.addEpilog(
      "Subscribes RGBD_FRAME; publishes SLAM_POSE for every frame it takes (skipped and refused ones too;\n"
      "with --frame-policy latest, frames dropped while it was busy get none), SLAM_KEYFRAME for each new "
      "keyframe\n"
      "(colour, depth, dynamic mask) and SLAM_KEYFRAME_POSES after local bundle adjustment; uses DETECTIONS\n"
      "for the dynamic stage.\n"
      "Example:\n"
      "  bmp-tracker --trajectory out/trajectory.txt --keyframe-trajectory out/keyframes.txt \\\n"
      "              --frame-log out/frames.tsv\n");
}

void applyDynamicModeOption(const ArgParser& args, TrackerConfig& config) {
  if (!args.given("dynamic-mode")) return;
  try {
    config.dynamic.mode = parseDynamicMode(args.value("dynamic-mode"));
  } catch (const std::invalid_argument& e) {
    throw ConfigError(std::string("--dynamic-mode: ") + e.what());
  }
}

namespace {

void applyOptions(const Config& config, const ArgParser& args, TrackerSettings& s) {
  applyDynamicModeOption(args, s.tracker);
  if (args.given("dynamic-mode"))
    config.section("tracker").section("dynamic").overridden("mode", args.value("dynamic-mode"),
                                                            "--dynamic-mode");
  const std::string policy = args.value("frame-policy");
  if (policy != "every" && policy != "latest")
    throw ConfigError("--frame-policy: must be every or latest, got '" + policy + "'");
  s.detections.reproducible = policy == "every";
}

}  // namespace

TrackerSettings trackerSettingsFromConfig(const Config& config, const ArgParser* args) {
  TrackerSettings s;
  s.tracker = trackerConfigFromConfig(config.section("tracker"));
  const Config process = config.section("process");
  s.frames_channel = process.get<std::string>("frames_channel", s.frames_channel);
  s.pose_channel = process.get<std::string>("pose_channel", s.pose_channel);
  s.keyframe_channel = process.get<std::string>("keyframe_channel", s.keyframe_channel);
  s.keyframe_poses_channel = process.get<std::string>("keyframe_poses_channel", s.keyframe_poses_channel);
  const int capacity = process.get<int>("frame_queue_capacity", static_cast<int>(s.frame_queue_capacity));
  process.check(capacity >= 1, "frame_queue_capacity", "must be at least 1");
  s.frame_queue_capacity = static_cast<std::size_t>(capacity);
  s.detections_channel = process.get<std::string>("detections_channel", s.detections_channel);
  DetectionPolicy& d = s.detections;
  d.wait_ms = process.get<double>("detections_wait_ms", d.wait_ms);
  process.check(d.wait_ms >= 0, "detections_wait_ms", "must not be negative");
  d.keyframe_hold_ms = process.get<double>("keyframe_hold_ms", d.keyframe_hold_ms);
  process.check(d.keyframe_hold_ms >= 0, "keyframe_hold_ms", "must not be negative");
  d.degraded_inliers = process.get<int>("degraded_inliers", d.degraded_inliers);
  process.check(d.degraded_inliers >= 0, "degraded_inliers", "must not be negative");
  if (args) applyOptions(config, *args, s);
  return s;
}

}  // namespace bmp::tracker

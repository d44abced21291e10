#include "tracker/tracker_settings.hpp"

#include "tracker/tracker_config.hpp"

namespace bmp::tracker {

void addTrackerOptions(ArgParser& args) {
  args.addOption("trajectory", "FILE",
                 "every tracked frame's pose (TUM format): written as tracked, replaced by the optimised "
                 "trajectory on exit");
  args.addOption("keyframe-trajectory", "FILE", "the keyframe poses (TUM format), likewise");
  args.addOption("idle-exit", "SECONDS",
                 "exit once no frame arrived for this long after the first (0: never)", "0");
  args.addEpilog(
      "Subscribes RGBD_FRAME; publishes SLAM_POSE for every frame, SLAM_KEYFRAME for each new keyframe\n"
      "(colour, depth, all-zero dynamic mask) and SLAM_KEYFRAME_POSES after local bundle adjustment.\n"
      "Example:\n"
      "  bmp-tracker --trajectory out/trajectory.txt --keyframe-trajectory out/keyframes.txt\n");
}

TrackerSettings trackerSettingsFromConfig(const Config& config) {
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
  return s;
}

}  // namespace bmp::tracker

// bmp-tracker: RGBD_FRAME in; SLAM_POSE (every frame), SLAM_KEYFRAME and SLAM_KEYFRAME_POSES out. The
// algorithm is bmp::tracker::Tracker and its LCM side TrackerNode (lcm/); this file reads the configuration,
// runs the node and writes the trajectories on exit.
#include "bmp/common/log.hpp"
#include "bmp/lcm/process.hpp"
#include "tracker/lcm/tracker_node.hpp"
#include "tracker/tracker_config.hpp"

namespace {

using namespace bmp;
using namespace bmp::tracker;

void addOptions(ArgParser& args) {
  args.addOption("trajectory", "FILE",
                 "every tracked frame's pose (TUM format): written as tracked, replaced by the optimised "
                 "trajectory on exit");
  args.addOption("keyframe-trajectory", "FILE", "the keyframe poses (TUM format), likewise");
  args.addOption("frame-policy", "every|latest",
                 "every: reproducible (wait for each frame's boxes, map inline; lockstep runs); latest: real "
                 "time, never wait",
                 "latest");
  args.addOption("dynamic-mode", "MODE", "override tracker.dynamic.mode: none|boxes|paper|depth|geometric");
  args.addOption("idle-exit", "SECONDS",
                 "exit once no frame arrived for this long after the first (0: never)", "0");
  args.addEpilog(
      "Subscribes RGBD_FRAME; publishes SLAM_POSE for every frame, SLAM_KEYFRAME for each new keyframe\n"
      "(colour, depth, dynamic mask) and SLAM_KEYFRAME_POSES after local bundle adjustment; uses DETECTIONS\n"
      "for the dynamic stage.\n"
      "Example:\n"
      "  bmp-tracker --trajectory out/trajectory.txt --keyframe-trajectory out/keyframes.txt\n");
}

int run(ProcessContext& ctx) {
  TrackerConfig config = trackerConfigFromConfig(ctx.config.section("tracker"));
  if (ctx.args.given("dynamic-mode")) config.dynamic.mode = parseDynamicMode(ctx.args.value("dynamic-mode"));
  const Config process = ctx.config.section("process");
  TrackerChannels channels;
  channels.frames = process.get<std::string>("frames_channel", channels.frames);
  channels.pose = process.get<std::string>("pose_channel", channels.pose);
  channels.keyframe = process.get<std::string>("keyframe_channel", channels.keyframe);
  channels.keyframe_poses = process.get<std::string>("keyframe_poses_channel", channels.keyframe_poses);
  channels.detections = process.get<std::string>("detections_channel", channels.detections);
  const int capacity = process.get<int>("frame_queue_capacity", 4);
  process.check(capacity >= 1, "frame_queue_capacity", "must be at least 1");
  DetectionPolicy policy;
  policy.wait_ms = process.get<double>("detections_wait_ms", policy.wait_ms);
  process.check(policy.wait_ms >= 0, "detections_wait_ms", "must not be negative");
  policy.keyframe_hold_ms = process.get<double>("keyframe_hold_ms", policy.keyframe_hold_ms);
  process.check(policy.keyframe_hold_ms >= 0, "keyframe_hold_ms", "must not be negative");
  const std::string frame_policy = ctx.args.value("frame-policy");
  if (frame_policy != "every" && frame_policy != "latest")
    throw ConfigError("--frame-policy must be every or latest, got '" + frame_policy + "'");
  policy.reproducible = frame_policy == "every";
  finishConfig(ctx);

  TrackerOutputs outputs;
  outputs.trajectory = ctx.args.value("trajectory");
  outputs.keyframe_trajectory = ctx.args.value("keyframe-trajectory");
  TrackerNode node(ctx, config, channels, static_cast<std::size_t>(capacity), outputs, policy);
  ctx.status.tick(true);
  node.run(ctx.args.number("idle-exit"));
  // Reached on every exit but a kill (the loop only ends by a stop request or idle-exit); after a kill the
  // files hold the live poses, written one by one.
  node.writeTrajectories();
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

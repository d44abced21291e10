// bmp-tracker: RGBD_FRAME in; SLAM_POSE (every frame), SLAM_KEYFRAME and SLAM_KEYFRAME_POSES out. The
// algorithm is bmp::tracker::Tracker, its settings and options TrackerSettings, its LCM side TrackerNode
// (lcm/); this file reads the settings, runs the node and writes the trajectories on exit.
#include <limits>

#include "bmp/common/arg_range.hpp"
#include "bmp/lcm/process.hpp"
#include "tracker/lcm/tracker_node.hpp"
#include "tracker/tracker_settings.hpp"

namespace {

using namespace bmp;
using namespace bmp::tracker;

int run(ProcessContext& ctx) {
  const TrackerSettings s = trackerSettingsFromConfig(ctx.config, ctx.args);
  const double idle_exit_s = numberIn(ctx.args, "idle-exit", 0.0, std::numeric_limits<double>::infinity());
  finishConfig(ctx);
  const TrackerChannels channels{s.frames_channel, s.pose_channel, s.keyframe_channel,
                                 s.keyframe_poses_channel, s.detections_channel};
  const TrackerOutputs outputs{ctx.args.value("trajectory"), ctx.args.value("keyframe-trajectory"),
                               ctx.args.value("frame-log")};
  TrackerNode node(ctx, s.tracker, channels, s.frame_queue_capacity, outputs, s.detections);
  ctx.status.tick(true);
  node.run(idle_exit_s);
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
                          "SLAM_POSE for every frame it takes, SLAM_KEYFRAME and SLAM_KEYFRAME_POSES.",
                          "tracker.yaml", addTrackerOptions, run});
}

#pragma once
// bmp-tracker's LCM side: frames in (a bounded queue, oldest gives way), the Tracker called on each, its
// results out as messages. The process's main only reads configuration and runs it.
#include <deque>
#include <memory>
#include <optional>
#include <string>

#include <bmp/rgbd_frame_t.hpp>

#include "bmp/common/timing.hpp"
#include "bmp/common/tum_trajectory.hpp"
#include "bmp/lcm/process.hpp"
#include "tracker/tracker.hpp"
#include "tracker/tracker_options.hpp"

namespace bmp::tracker {

struct TrackerChannels {
  std::string frames = channels::kFrames;
  std::string pose = channels::kPose;
  std::string keyframe = channels::kKeyframe;
  std::string keyframe_poses = channels::kKeyframePoses;
};

// Where the trajectories go (empty: not written). Each is written pose by pose while tracking, so a killed
// process leaves what it had, and replaced whole by the optimised one at a clean exit.
struct TrackerOutputs {
  std::string trajectory;
  std::string keyframe_trajectory;
};

class TrackerNode {
 public:
  // Opens the outputs at once: an unwritable path fails at start-up, naming it (TrajectoryError).
  TrackerNode(ProcessContext& ctx, TrackerConfig config, TrackerChannels channels, std::size_t queue_capacity,
              const TrackerOutputs& outputs);

  // Until a stop is requested, or idle_exit_s (> 0) seconds pass without a frame after the first.
  void run(double idle_exit_s);
  // Replaces the live files with the trajectories after local mapping's corrections; call after run().
  void writeTrajectories();

 private:
  void process(const rgbd_frame_t& msg);

  ProcessContext& ctx_;
  TrackerConfig config_;
  TrackerChannels channels_;
  std::size_t capacity_;
  std::deque<rgbd_frame_t> pending_;
  std::unique_ptr<Tracker> tracker_;
  cv::Mat empty_mask_;  // no dynamic handling yet: nothing is masked
  TrackerOutputs outputs_;
  std::optional<TumTrajectoryStream> live_trajectory_;
  std::optional<TumTrajectoryStream> live_keyframes_;
  TimingStats timing_;
  int64_t lost_ = 0;
};

}  // namespace bmp::tracker

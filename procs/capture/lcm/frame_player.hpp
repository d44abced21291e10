#pragma once
// Plays a FrameSource onto LCM: paces, publishes RGBD_FRAME, waits for the consumer in lockstep mode,
// reports progress and keeps the ground truth of what it played.
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "bmp/common/tum_trajectory.hpp"
#include "bmp/lcm/channels.hpp"
#include "bmp/lcm/process.hpp"
#include "capture/frame_source.hpp"
#include "capture/pacer.hpp"

namespace bmp::capture {

struct PlayerOptions {
  std::string channel = channels::kFrames;
  // Lockstep: the next frame goes out once every one of these channels has answered this one (a slam_pose_t
  // or detections_t carrying its seq), so the slowest consumer sets the pace and none falls behind.
  std::vector<std::string> ack_channels{channels::kPose};
  RateMode mode = RateMode::kRealtime;
  double speed = 1.0;
  double lockstep_timeout_s = 5.0;
  double progress_every_s = 2.0;
  std::string masks_out;  // folder for dynamic masks (synthetic only); "" = none
};

struct PlayerSummary {
  int64_t published = 0;
  int64_t lockstep_timeouts = 0;
  double elapsed_s = 0.0;
  double frames_per_second() const {
    return elapsed_s > 0 ? static_cast<double>(published) / elapsed_s : 0.0;
  }
  Trajectory groundtruth;  // exact poses of the played frames, when the source knows them
  bool interrupted = false;
};

class FramePlayer {
 public:
  FramePlayer(LcmNode& lcm, StopSignal& stop, StatusReporter& status, PlayerOptions options);
  PlayerSummary play(FrameSource& source);

 private:
  bool waitForAck(int64_t seq);
  void onAnswer(const void* data, uint32_t size, const ReceivedInfo& info);
  void writeMask(const CapturedFrame& frame);

  LcmNode& lcm_;
  StopSignal& stop_;
  StatusReporter& status_;
  PlayerOptions options_;
  std::map<std::string, int64_t> last_answered_seq_;  // per answer channel
};

}  // namespace bmp::capture

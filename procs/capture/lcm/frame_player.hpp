#pragma once
// Plays a FrameSource onto LCM: paces, publishes RGBD_FRAME, waits for the consumer in lockstep mode,
// reports progress and keeps the ground truth of what it played.
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include <bmp/rgbd_frame_t.hpp>

#include "bmp/common/tum_trajectory.hpp"
#include "bmp/lcm/process.hpp"
#include "capture/capture_settings.hpp"  // PlayerOptions
#include "capture/frame_source.hpp"
#include "capture/pacer.hpp"

namespace bmp::capture {

struct PlayerSummary {
  int64_t published = 0;
  int64_t lockstep_timeouts = 0;
  int64_t resent = 0;  // lockstep: frames published again because their answers were late
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
  // on_truth, when set, receives each played frame's true pose as it is published (the source knows it).
  PlayerSummary play(FrameSource& source, const std::function<void(const StampedPose&)>& on_truth = {});

 private:
  // Lockstep: waits for every answer to msg, publishing it again when they are late; false on timeout.
  bool waitForAck(const rgbd_frame_t& msg, PlayerSummary& summary);
  double resendAfterMs() const;
  void remember(int64_t seq, int64_t utime);
  void onAnswer(const void* data, uint32_t size, const ReceivedInfo& info);
  void writeMask(const CapturedFrame& frame);

  LcmNode& lcm_;
  StopSignal& stop_;
  StatusReporter& status_;
  PlayerOptions options_;
  std::map<std::string, int64_t> last_answered_seq_;  // per answer channel
  // What this capture published lately (seq -> utime): an answer counts only when both match a frame we
  // sent, so a forged or stray answer (another capture's, seq = INT64_MAX) can never release a frame.
  std::map<int64_t, int64_t> published_utime_;
  int64_t stray_answers_ = 0;
  std::deque<double> answer_ms_;  // the latest frames' answer times (lockstep)
};

}  // namespace bmp::capture

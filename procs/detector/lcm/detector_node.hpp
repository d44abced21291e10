#pragma once
// bmp-detector's LCM side: RGBD_FRAME in, handed to the DetectionWorker's thread; its results out as
// DETECTIONS. The LCM thread only receives and publishes, so it never waits for the network. The process's
// main only reads the settings and runs it.
#include <bmp/detections_t.hpp>
#include <bmp/rgbd_frame_t.hpp>

#include "bmp/common/timing.hpp"
#include "bmp/common/warning_throttle.hpp"
#include "bmp/lcm/frame_checks.hpp"
#include "bmp/lcm/last_answer.hpp"
#include "bmp/lcm/process.hpp"
#include "detector/detection_worker.hpp"
#include "detector/detector.hpp"
#include "detector/detector_settings.hpp"
#include "detector/wakeup.hpp"

namespace bmp::detector {

class DetectorNode {
 public:
  // Loads the model and subscribes. A missing or broken model is a ConfigError (exit code 2 before any
  // frame is read).
  DetectorNode(ProcessContext& ctx, const DetectorSettings& settings);
  DetectorNode(const DetectorNode&) = delete;
  DetectorNode& operator=(const DetectorNode&) = delete;

  // Until a stop is requested; returns the exit code (1 if receiving from LCM fails). Logs the counts and
  // per-frame times at the end.
  int run();

 private:
  void receive(const rgbd_frame_t& msg);
  void publishResults();
  // How a frame that cannot be processed is answered.
  enum class SkipAnswer {
    kRemembered,  // answered, and the answer repeated for a resend
    // Refused on arrival: judged and answered again if sent again, so not remembered (it would replace
    // the answer a resend of the real frame before it repeats).
    kOnce,
    // A damaged copy of a frame accepted (FrameStream::Verdict::copies_accepted): not answered, as the
    // answer would go out under the real frame's seq and stamp and stand for its boxes.
    kNone,
  };
  // A frame that cannot be processed is warned about, counted, and answered as `how` says (no boxes, the
  // reason), so lockstep never waits in vain.
  void skip(const FrameResult& failed, SkipAnswer how = SkipAnswer::kRemembered);
  void answer(const detections_t& msg);  // publishes and remembers it for a repeated frame

  ProcessContext& ctx_;
  DetectorSettings settings_;
  Detector detector_;
  std::string model_name_;
  Wakeup wakeup_;
  TimingStats frame_times_;
  FrameStream stream_;  // refuses unusable or out-of-order frames, counts those lost upstream
  LastAnswer<detections_t> last_answer_;  // published again for a frame capture resends
  WarningThrottle warnings_;              // a flood of bad frames cannot flood the log
  DetectionWorker worker_;                // last: its thread stops first, before what it uses goes
};

}  // namespace bmp::detector

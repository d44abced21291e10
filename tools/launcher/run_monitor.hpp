#pragma once
// What a run did, from the processes' own messages: every SLAM_POSE (state, tracking time), DETECTIONS
// (inference time) and PROCESS_STATUS (each process's counts) heard on the run's LCM URL, on a thread of its
// own. The design's evaluation asks for tracking time, detector time and end-to-end rate, each as median
// and p95; the heartbeats say, per process, how many frames it lost and why.
#include <atomic>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <utility>

#include <bmp/slam_pose_t.hpp>

#include "bmp/common/timing.hpp"
#include "bmp/lcm/channels.hpp"
#include "bmp/lcm/lcm_node.hpp"

namespace bmp::launcher {

// One process's last heartbeat.
struct ProcessFigures {
  std::string name;
  int64_t instance = 0;
  int8_t state = 0;       // process_status_t::STATE_*
  int64_t received = 0;   // inputs that arrived
  int64_t processed = 0;  // inputs it used (capture: frames published)
  int64_t dropped = 0;    // inputs it chose not to process: its own queue overflowed (capture: bad files)
  int64_t lost = 0;       // inputs that never arrived: gaps in the sender's sequence
  int64_t malformed = 0;  // inputs that did not decode or were refused (with a reason in its log)
  std::string message;    // its last warning, or its own figures (the mapper's)
};

struct RunSummary {
  int64_t poses = 0;  // SLAM_POSE messages: one per frame the tracker answered
  int64_t ok = 0, lost = 0, relocalised = 0, initialising = 0, skipped = 0, degraded = 0;
  TimingStats tracking_ms;      // processing_ms of the tracked frames
  TimingStats position_std_mm;  // position_std_m of the frames that have one (tracked), in mm
  int64_t detections = 0;       // DETECTIONS messages
  int64_t detections_skipped = 0;
  TimingStats detector_ms;             // inference_ms of the processed frames
  TimingStats frame_period_ms;         // wall-clock time between consecutive poses: the end-to-end pace
  double answered_per_second() const;  // from the median period; NaN with fewer than two poses
  // The last heartbeat of each process start, by name then instance.
  std::map<std::pair<std::string, int64_t>, ProcessFigures> processes;
};

std::string formatSummaryText(const RunSummary& summary);
std::string formatSummaryJson(const RunSummary& summary);

class RunMonitor {
 public:
  // Listens on url until destroyed. Throws LcmError naming the URL when it cannot be opened.
  RunMonitor(const std::string& url, const std::string& pose_channel, const std::string& detections_channel,
             const std::string& status_channel = channels::kProcessStatus);
  ~RunMonitor();
  RunMonitor(const RunMonitor&) = delete;
  RunMonitor& operator=(const RunMonitor&) = delete;

  RunSummary summary() const;

 private:
  void onPose(const slam_pose_t& m);
  // The frame an answer is for: one answered again (capture resent the frame) is counted once.
  struct LastFrame {
    int64_t seq = -1, utime = -1;
    bool isNew(int64_t s, int64_t u) {
      const bool fresh = s != seq || u != utime;
      seq = s;
      utime = u;
      return fresh;
    }
  };
  LastFrame last_pose_, last_detections_;
  LcmNode lcm_;
  mutable std::mutex mutex_;
  RunSummary summary_;
  Stopwatch since_last_pose_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace bmp::launcher

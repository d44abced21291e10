#pragma once
// What a run did, from the processes' own messages: every SLAM_POSE (state, tracking time) and DETECTIONS
// (inference time) heard on the run's LCM URL, on a thread of its own. The design's evaluation asks for
// tracking time, detector time and end-to-end rate, each as median and p95: this is where they come from.
#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "bmp/common/timing.hpp"
#include "bmp/lcm/lcm_node.hpp"

namespace bmp::launcher {

struct RunSummary {
  int64_t poses = 0;  // SLAM_POSE messages: one per frame the tracker answered
  int64_t ok = 0, lost = 0, relocalised = 0, initialising = 0, skipped = 0;
  TimingStats tracking_ms;  // processing_ms of the tracked frames
  int64_t detections = 0;   // DETECTIONS messages
  int64_t detections_skipped = 0;
  TimingStats detector_ms;             // inference_ms of the processed frames
  TimingStats frame_period_ms;         // wall-clock time between consecutive poses: the end-to-end pace
  double answered_per_second() const;  // from the median period; NaN with fewer than two poses
};

std::string formatSummaryText(const RunSummary& summary);
std::string formatSummaryJson(const RunSummary& summary);

class RunMonitor {
 public:
  // Listens on url until destroyed. Throws LcmError naming the URL when it cannot be opened.
  RunMonitor(const std::string& url, const std::string& pose_channel, const std::string& detections_channel);
  ~RunMonitor();
  RunMonitor(const RunMonitor&) = delete;
  RunMonitor& operator=(const RunMonitor&) = delete;

  RunSummary summary() const;

 private:
  LcmNode lcm_;
  mutable std::mutex mutex_;
  RunSummary summary_;
  Stopwatch since_last_pose_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace bmp::launcher

#include "launcher/run_monitor.hpp"

#include <cmath>
#include <sstream>

#include <bmp/detections_t.hpp>
#include <bmp/slam_pose_t.hpp>

#include "bmp/common/number_format.hpp"

namespace bmp::launcher {

namespace {

std::string number(double v, int digits) {
  return formatFixed(v, digits, "null");
}

std::string jsonTiming(const TimingStats& t) {
  return "{\"count\": " + std::to_string(t.count()) + ", \"median\": " + number(t.median(), 3) +
         ", \"p95\": " + number(t.p95(), 3) + "}";
}

std::string textTiming(const TimingStats& t) {
  if (t.empty()) return "-";
  return "median " + number(t.median(), 1) + " ms, p95 " + number(t.p95(), 1) + " ms";
}

}  // namespace

double RunSummary::answered_per_second() const {
  return frame_period_ms.empty() ? NAN : 1000.0 / frame_period_ms.median();
}

std::string formatSummaryText(const RunSummary& s) {
  std::ostringstream out;
  out << "run summary (from the processes' own messages)\n";
  out << "  tracker:   " << s.poses << " frames answered: " << s.ok << " ok, " << s.relocalised
      << " relocalised, " << s.lost << " lost, " << s.initialising << " initialising, " << s.skipped
      << " skipped; tracking " << textTiming(s.tracking_ms) << "\n";
  out << "  detector:  " << s.detections << " frames answered, " << s.detections_skipped << " skipped; "
      << textTiming(s.detector_ms) << "\n";
  out << "  end to end: " << number(s.answered_per_second(), 1)
      << " frames/s (pose to pose: " << textTiming(s.frame_period_ms) << ")\n";
  return out.str();
}

std::string formatSummaryJson(const RunSummary& s) {
  std::ostringstream out;
  out << "{\n  \"tracker\": {\"frames\": " << s.poses << ", \"ok\": " << s.ok
      << ", \"relocalised\": " << s.relocalised << ", \"lost\": " << s.lost
      << ", \"initialising\": " << s.initialising << ", \"skipped\": " << s.skipped
      << ", \"tracking_ms\": " << jsonTiming(s.tracking_ms) << "},\n";
  out << "  \"detector\": {\"frames\": " << s.detections << ", \"skipped\": " << s.detections_skipped
      << ", \"per_frame_ms\": " << jsonTiming(s.detector_ms) << "},\n";
  out << "  \"end_to_end\": {\"frames_per_second\": " << number(s.answered_per_second(), 3)
      << ", \"pose_period_ms\": " << jsonTiming(s.frame_period_ms) << "}\n}\n";
  return out.str();
}

RunMonitor::RunMonitor(const std::string& url, const std::string& pose_channel,
                       const std::string& detections_channel)
    : lcm_(url) {
  lcm_.subscribe<slam_pose_t>(pose_channel, [this](const slam_pose_t& m, const ReceivedInfo&) {
    std::lock_guard<std::mutex> lock(mutex_);
    RunSummary& s = summary_;
    ++s.poses;
    switch (m.state) {
      case slam_pose_t::STATE_OK:
        ++s.ok;
        break;
      case slam_pose_t::STATE_LOST:
        ++s.lost;
        break;
      case slam_pose_t::STATE_RELOCALISED:
        ++s.relocalised;
        break;
      case slam_pose_t::STATE_INITIALISING:
        ++s.initialising;
        break;
      default:
        ++s.skipped;
        break;
    }
    if (m.state != slam_pose_t::STATE_SKIPPED) s.tracking_ms.add(m.processing_ms);
    if (s.poses > 1) s.frame_period_ms.add(since_last_pose_.elapsedMs());
    since_last_pose_.restart();
  });
  lcm_.subscribe<detections_t>(detections_channel, [this](const detections_t& m, const ReceivedInfo&) {
    std::lock_guard<std::mutex> lock(mutex_);
    ++summary_.detections;
    if (!m.skipped.empty()) {
      ++summary_.detections_skipped;
      return;
    }
    summary_.detector_ms.add(m.inference_ms);
  });
  thread_ = std::thread([this] {
    while (!stop_.load()) lcm_.handle(50);
  });
}

RunMonitor::~RunMonitor() {
  stop_.store(true);
  if (thread_.joinable()) thread_.join();
}

RunSummary RunMonitor::summary() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return summary_;
}

}  // namespace bmp::launcher

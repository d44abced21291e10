#include "launcher/run_monitor.hpp"

#include <cmath>
#include <sstream>

#include <bmp/detections_t.hpp>
#include <bmp/process_status_t.hpp>
#include <bmp/slam_pose_t.hpp>

#include "bmp/common/json_text.hpp"
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

// "bmp-tracker", or "bmp-tracker (2)" for the second start of that name: names repeat, instances do not.
std::vector<std::pair<std::string, const ProcessFigures*>> labelled(const RunSummary& s) {
  std::vector<std::pair<std::string, const ProcessFigures*>> out;
  std::map<std::string, int> seen;
  for (const auto& [key, p] : s.processes) {
    const int n = ++seen[p.name];
    out.emplace_back(n == 1 ? p.name : p.name + " (" + std::to_string(n) + ")", &p);
  }
  return out;
}

std::string textProcess(const std::string& label, const ProcessFigures& p) {
  std::ostringstream out;
  out << "  " << label << ": ";
  if (p.name == "bmp-capture") {
    out << p.processed << " frames published, " << p.dropped << " source frames skipped (bad files), "
        << p.malformed << " malformed or stray answers ignored";
  } else {
    out << p.received << " received, " << p.processed << " processed, " << p.dropped
        << " dropped (own queue), " << p.lost << " lost (never arrived), " << p.malformed
        << " malformed or refused";
  }
  out << (p.state == process_status_t::STATE_FINISHED ? "" : " (no final heartbeat)") << "\n";
  // The mapper's heartbeat message carries its own figures (keyframes, points, memory).
  if (p.name == "bmp-mapper" && !p.message.empty()) out << "  mapper:    " << p.message << "\n";
  return out.str();
}

std::string jsonProcess(const ProcessFigures& p) {
  std::ostringstream out;
  out << "{\"name\": " << jsonString(p.name)
      << ", \"finished\": " << (p.state == process_status_t::STATE_FINISHED ? "true" : "false")
      << ", \"received\": " << p.received << ", \"processed\": " << p.processed
      << ", \"dropped\": " << p.dropped << ", \"lost\": " << p.lost << ", \"malformed\": " << p.malformed
      << ", \"message\": " << jsonString(p.message) << "}";
  return out.str();
}

}  // namespace

double RunSummary::answered_per_second() const {
  return frame_period_ms.empty() ? NAN : 1000.0 / frame_period_ms.median();
}

std::string formatSummaryText(const RunSummary& s) {
  std::ostringstream out;
  out << "run summary (from the processes' own messages)\n";
  out << "  tracker:   " << s.poses << " frames answered: " << s.ok << " ok, " << s.relocalised
      << " relocalised, " << s.degraded << " degraded, " << s.lost << " lost, " << s.initialising
      << " initialising, " << s.skipped << " skipped; tracking " << textTiming(s.tracking_ms) << "\n";
  if (!s.position_std_mm.empty())
    out << "  poses:     position std median " << number(s.position_std_mm.median(), 1) << " mm, p95 "
        << number(s.position_std_mm.p95(), 1) << " mm (how well each frame's keypoints pin it)\n";
  out << "  detector:  " << s.detections << " frames answered, " << s.detections_skipped << " skipped; "
      << textTiming(s.detector_ms) << "\n";
  // Two poses at least make a pace; fewer (a run that stopped at once) have none to show.
  if (s.frame_period_ms.empty())
    out << "  end to end: - (fewer than two poses)\n";
  else
    out << "  end to end: " << number(s.answered_per_second(), 1)
        << " frames/s (pose to pose: " << textTiming(s.frame_period_ms) << ")\n";
  if (!s.processes.empty()) out << "frames per process (from each one's last heartbeat)\n";
  for (const auto& [label, p] : labelled(s)) out << textProcess(label, *p);
  return out.str();
}

std::string formatSummaryJson(const RunSummary& s) {
  std::ostringstream out;
  out << "{\n  \"tracker\": {\"frames\": " << s.poses << ", \"ok\": " << s.ok
      << ", \"relocalised\": " << s.relocalised << ", \"degraded\": " << s.degraded
      << ", \"lost\": " << s.lost << ", \"initialising\": " << s.initialising
      << ", \"skipped\": " << s.skipped << ", \"tracking_ms\": " << jsonTiming(s.tracking_ms)
      << ", \"position_std_mm\": " << jsonTiming(s.position_std_mm) << "},\n";
  out << "  \"detector\": {\"frames\": " << s.detections << ", \"skipped\": " << s.detections_skipped
      << ", \"per_frame_ms\": " << jsonTiming(s.detector_ms) << "},\n";
  out << "  \"end_to_end\": {\"frames_per_second\": " << number(s.answered_per_second(), 3)
      << ", \"pose_period_ms\": " << jsonTiming(s.frame_period_ms) << "},\n";
  out << "  \"processes\": [";
  bool first = true;
  for (const auto& [key, p] : s.processes) {
    out << (first ? "\n    " : ",\n    ") << jsonProcess(p);
    first = false;
  }
  out << (first ? "]\n}\n" : "\n  ]\n}\n");
  return out.str();
}

namespace {

// Anyone can publish poses and answers: a NaN, infinite or negative time would spoil the medians (and
// std::sort on NaN is undefined), so such a time is left out of them; the message still counts.
bool plausibleMs(float ms) {
  return std::isfinite(ms) && ms >= 0.0f;
}

}  // namespace

void RunMonitor::onPose(const slam_pose_t& m) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!last_pose_.isNew(m.seq, m.utime)) return;  // the answer to a frame capture resent, again
  const int8_t state = m.state;
  const float processing_ms = m.processing_ms;
  RunSummary& s = summary_;
  ++s.poses;
  switch (state) {
    case slam_pose_t::STATE_OK:
      ++s.ok;
      break;
    case slam_pose_t::STATE_DEGRADED:
      ++s.degraded;
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
  if (state != slam_pose_t::STATE_SKIPPED && plausibleMs(processing_ms)) s.tracking_ms.add(processing_ms);
  const float position_std_m = m.position_std_m;
  if (std::isfinite(position_std_m) && position_std_m >= 0.0f) s.position_std_mm.add(position_std_m * 1000.0);
  if (s.poses > 1) s.frame_period_ms.add(since_last_pose_.elapsedMs());
  since_last_pose_.restart();
}

RunMonitor::RunMonitor(const std::string& url, const std::string& pose_channel,
                       const std::string& detections_channel, const std::string& status_channel)
    : lcm_(url) {
  lcm_.subscribe<slam_pose_t>(pose_channel, [this](const slam_pose_t& m, const ReceivedInfo&) { onPose(m); });
  lcm_.subscribe<detections_t>(detections_channel, [this](const detections_t& m, const ReceivedInfo&) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!last_detections_.isNew(m.seq, m.utime)) return;
    ++summary_.detections;
    if (!m.skipped.empty()) {
      ++summary_.detections_skipped;
      return;
    }
    if (plausibleMs(m.inference_ms)) summary_.detector_ms.add(m.inference_ms);
  });
  lcm_.subscribe<process_status_t>(status_channel, [this](const process_status_t& m, const ReceivedInfo&) {
    std::lock_guard<std::mutex> lock(mutex_);
    // Anyone can publish heartbeats: a flood of invented names must not grow the summary without bound.
    constexpr std::size_t kMaxProcesses = 64;
    const std::pair<std::string, int64_t> key{m.name, m.instance};
    if (summary_.processes.size() >= kMaxProcesses && summary_.processes.count(key) == 0) return;
    ProcessFigures& p = summary_.processes[key];
    p = {m.name, m.instance, m.state, m.received, m.processed, m.dropped, m.lost, m.malformed, m.message};
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

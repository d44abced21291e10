#pragma once
// Everything bmp-tracker reads from its configuration file, read and checked in one place before any work
// starts: the tracker's tunables ("tracker") and how the process is wired ("process": channels, queue).
#include <cstddef>
#include <string>

#include "bmp/common/arg_parser.hpp"
#include "bmp/common/config.hpp"
#include "bmp/lcm/channels.hpp"  // channel names only: no LCM
#include "tracker/tracker_options.hpp"

namespace bmp::tracker {

// How the tracker uses the detector's answers (detection_book.hpp states the rule).
struct DetectionPolicy {
  // Lockstep (--frame-policy every): wait for each frame's answer (up to wait_ms) and run local mapping
  // inline, so the same input gives the same trajectory. Real time (latest): never wait, map in a thread.
  bool reproducible = false;
  double wait_ms = 3000.0;
  // Real time: a keyframe whose frame's answer has not come is held this long for it, so the mapper gets
  // the mask with the boxes; its map points take the late observation either way.
  double keyframe_hold_ms = 500.0;
  // An OK pose supported by fewer inliers than this is published as DEGRADED (0: never). Not about
  // detections: it rides here because this is the process section's part the node is given.
  int degraded_inliers = 50;
};

struct TrackerSettings {
  TrackerConfig tracker;
  std::string frames_channel = channels::kFrames;
  std::string pose_channel = channels::kPose;
  std::string keyframe_channel = channels::kKeyframe;
  std::string keyframe_poses_channel = channels::kKeyframePoses;
  std::string detections_channel = channels::kDetections;
  std::size_t frame_queue_capacity = 4;  // frames waiting while one is tracked; the oldest gives way
  DetectionPolicy detections;
};

// bmp-tracker's own options (--trajectory, --keyframe-trajectory, --frame-policy, --dynamic-mode,
// --idle-exit) and --help epilog.
void addTrackerOptions(ArgParser& args);

// --dynamic-mode, when given, over config.dynamic.mode (ConfigError naming the option for a bad name).
void applyDynamicModeOption(const ArgParser& args, TrackerConfig& config);

// Reads sections "tracker" (trackerConfigFromConfig) and "process" of config. Throws ConfigError naming the
// file and key for a wrong type or value; unknown keys are left for the caller's Config::finish().
// With args, --frame-policy and --dynamic-mode override the file (ConfigError naming the option).
TrackerSettings trackerSettingsFromConfig(const Config& config, const ArgParser* args = nullptr);
inline TrackerSettings trackerSettingsFromConfig(const Config& config, const ArgParser& args) {
  return trackerSettingsFromConfig(config, &args);
}

}  // namespace bmp::tracker

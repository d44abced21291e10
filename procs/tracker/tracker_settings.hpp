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

struct TrackerSettings {
  TrackerConfig tracker;
  std::string frames_channel = channels::kFrames;
  std::string pose_channel = channels::kPose;
  std::string keyframe_channel = channels::kKeyframe;
  std::string keyframe_poses_channel = channels::kKeyframePoses;
  std::size_t frame_queue_capacity = 4;  // frames waiting while one is tracked; the oldest gives way
};

// bmp-tracker's own options (--trajectory, --keyframe-trajectory, --idle-exit) and --help epilog.
void addTrackerOptions(ArgParser& args);

// Reads sections "tracker" (trackerConfigFromConfig) and "process" of config. Throws ConfigError naming the
// file and key for a wrong type or value; unknown keys are left for the caller's Config::finish().
TrackerSettings trackerSettingsFromConfig(const Config& config);

}  // namespace bmp::tracker

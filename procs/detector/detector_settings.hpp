#pragma once
// Everything bmp-detector reads from its configuration file, read and checked in one place before any work
// starts: the detector's tunables, where the level table is, how frames reach the worker, the channels.
#include <cstddef>
#include <optional>
#include <string>

#include "bmp/common/config.hpp"
#include "detector/detection_worker.hpp"
#include "detector/detector_config.hpp"

namespace bmp::detector {

struct DetectorSettings {
  DetectorConfig detector;
  std::string dynamic_classes_path;  // resolved: absolute, or relative to the working folder
  QueueMode mode = QueueMode::kLatest;
  std::size_t queue_capacity = 64;  // frames waiting in kEvery mode
  // kLatest (real time): the process's nice value. Its answers are optional there (the tracker lets the
  // newest earlier boxes stand in), the tracker's poses are not, so on a shared CPU the detector yields.
  int latest_nice = 10;
  std::string frames_channel;
  std::string detections_channel;
};

// Reads sections "model" and "detection" (detectorConfigFromYaml), "dynamic_classes" (relative to the folder
// of the configuration file, or to fallback_dir when the configuration is not a file), "process" (mode,
// queue_capacity, latest_nice) and "channels" (frames, detections). mode_override (the --mode option)
// replaces process.mode. Throws ConfigError naming the file and key for a wrong type or value; unknown keys
// are left for the caller's Config::finish().
DetectorSettings detectorSettingsFromConfig(const Config& config,
                                            const std::optional<std::string>& mode_override,
                                            const std::string& fallback_dir);

}  // namespace bmp::detector

#include "detector/detector_settings.hpp"

#include <filesystem>
#include <stdexcept>

// Only the default channel names: a header of constants, no LCM.
#include "bmp/lcm/channels.hpp"

namespace bmp::detector {

namespace {

// A relative path in the configuration is relative to the folder of the file that names it.
std::string besideConfig(const Config& config, const std::string& path, const std::string& fallback_dir) {
  if (std::filesystem::path(path).is_absolute()) return path;
  const std::filesystem::path origin(config.origin());
  const auto dir =
      std::filesystem::is_regular_file(origin) ? origin.parent_path() : std::filesystem::path(fallback_dir);
  return (dir / path).string();
}

}  // namespace

DetectorSettings detectorSettingsFromConfig(const Config& config,
                                            const std::optional<std::string>& mode_override,
                                            const std::string& fallback_dir) {
  DetectorSettings s;
  s.detector = detectorConfigFromYaml(config);
  s.dynamic_classes_path =
      besideConfig(config, config.get<std::string>("dynamic_classes", "dynamic_classes.yaml"), fallback_dir);
  const Config process = config.section("process");
  const std::string mode = process.get<std::string>("mode", "latest");
  const int capacity = process.get<int>("queue_capacity", static_cast<int>(s.queue_capacity));
  s.latest_nice = process.get<int>("latest_nice", s.latest_nice);
  const Config channels = config.section("channels");
  s.frames_channel = channels.get<std::string>("frames", channels::kFrames);
  s.detections_channel = channels.get<std::string>("detections", channels::kDetections);

  const std::string& chosen = mode_override ? *mode_override : mode;
  if (mode_override) process.overridden("mode", *mode_override, "--mode");
  std::string mode_error;
  try {
    s.mode = parseQueueMode(chosen);
  } catch (const std::invalid_argument& e) {
    mode_error = e.what();
  }
  process.check(mode_error.empty(), "mode", "or --mode: " + mode_error);
  process.check(capacity >= 1, "queue_capacity", "must be >= 1");
  s.queue_capacity = static_cast<std::size_t>(capacity);
  process.check(s.latest_nice >= 0 && s.latest_nice <= 19, "latest_nice", "must be in [0, 19]");
  return s;
}

}  // namespace bmp::detector

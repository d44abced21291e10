#pragma once
// TrackerConfig from a configuration section (config/tracker.yaml). Absent keys keep the struct's defaults;
// every value is checked (ranges, min <= max pairs) and one out of range throws ConfigError naming file and
// key.
#include "bmp/common/config.hpp"
#include "tracker/tracker_options.hpp"

namespace bmp::tracker {

TrackerConfig trackerConfigFromConfig(const Config& section);

}  // namespace bmp::tracker

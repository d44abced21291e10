#pragma once
// TrackerConfig from a configuration section (config/tracker.yaml). Absent keys keep the struct's defaults;
// values out of range throw ConfigError naming the key.
#include "bmp/common/config.hpp"
#include "tracker/tracker_options.hpp"

namespace bmp::tracker {

TrackerConfig trackerConfigFromConfig(const Config& section);

}  // namespace bmp::tracker

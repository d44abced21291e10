#pragma once
// MapperSettings from the `mapper` section of config/mapper.yaml: the one place that reads and checks them.
#include "bmp/common/config.hpp"
#include "mapper/mapper_settings.hpp"

namespace bmp::mapper {

// Absent keys keep the struct's defaults; a value out of range throws ConfigError naming file and key.
MapperSettings mapperSettingsFromConfig(const Config& section);

}  // namespace bmp::mapper

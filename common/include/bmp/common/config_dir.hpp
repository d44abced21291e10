#pragma once
// Where the repository's config/ folder is, for processes and tools alike (default configuration files,
// cameras/, dynamic_classes.yaml).
#include <string>

namespace bmp {

// $BMP_CONFIG_DIR, else the source tree's config/ this build came from, else ./config.
std::string configDir();

}  // namespace bmp

#include "bmp/common/config_dir.hpp"

#include <cstdlib>
#include <filesystem>

#ifndef BMP_SOURCE_CONFIG_DIR
#define BMP_SOURCE_CONFIG_DIR "config"
#endif

namespace bmp {

std::string configDir() {
  if (const char* env = std::getenv("BMP_CONFIG_DIR"); env != nullptr && *env != '\0') return env;
  if (std::filesystem::is_directory(BMP_SOURCE_CONFIG_DIR)) return BMP_SOURCE_CONFIG_DIR;
  return "config";
}

}  // namespace bmp

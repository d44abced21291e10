#include "bmp/common/shared_paths.hpp"

#include <cstdlib>
#include <filesystem>

namespace bmp {

std::string sharedDir() {
  if (const char* env = std::getenv("BMP_SHARED"); env != nullptr && *env != '\0') return env;
  return BMP_SHARED_DEFAULT;
}

std::string resolveSharedPath(const std::string& path) {
  if (path.empty() || std::filesystem::path(path).is_absolute()) return path;
  return (std::filesystem::path(sharedDir()) / path).lexically_normal().string();
}

}  // namespace bmp

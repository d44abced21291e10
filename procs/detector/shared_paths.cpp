#include "detector/shared_paths.hpp"

#include "bmp/common/shared_paths.hpp"

namespace bmp::detector {

std::string sharedDir() {
  return bmp::sharedDir();
}

std::string resolveSharedPath(const std::string& path) {
  return bmp::resolveSharedPath(path);
}

}  // namespace bmp::detector

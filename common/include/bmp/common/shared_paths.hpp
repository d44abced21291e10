#pragma once
// Models, images and data sets live in the shared folder beside the checkout, never in the repository:
// processes and tools resolve the relative paths of their configuration against it.
#include <string>

namespace bmp {

// $BMP_SHARED when set, else <repository>/../shared.
std::string sharedDir();
// An absolute path is returned unchanged; a relative one is taken relative to sharedDir().
std::string resolveSharedPath(const std::string& path);

}  // namespace bmp

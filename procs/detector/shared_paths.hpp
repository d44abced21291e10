#pragma once
// Models and data live in the shared folder beside the checkout, never in the repository.
#include <string>

namespace bmp::detector {

// $BMP_SHARED when set, else <repository>/../shared.
std::string sharedDir();
// An absolute path is returned unchanged; a relative one is taken relative to sharedDir().
std::string resolveSharedPath(const std::string& path);

}  // namespace bmp::detector

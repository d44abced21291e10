#pragma once
// The detector's name for the shared-folder helpers, which live in bmp_common (bmp/common/shared_paths.hpp)
// so that capture resolves its images the same way.
#include <string>

namespace bmp::detector {

// $BMP_SHARED when set, else <repository>/../shared.
std::string sharedDir();
// An absolute path is returned unchanged; a relative one is taken relative to sharedDir().
std::string resolveSharedPath(const std::string& path);

}  // namespace bmp::detector

#pragma once
// Writes a synthetic sequence as a TUM-format folder, so it can be replayed like any recorded dataset.
#include <functional>
#include <stdexcept>
#include <string>

#include "capture/synthetic_scene.hpp"

namespace bmp::capture {

// Creates dir with rgb/, depth/ (16-bit PNG), mask/ (8-bit PNG, 255 on moving objects), rgb.txt, depth.txt
// and groundtruth.txt; files are named by stamp ("1000.033333.png"). `progress`, when set, is called after
// each frame with (frames done, total). Throws std::runtime_error when a file cannot be written.
void writeTumFolder(const SyntheticScene& scene, const std::string& dir,
                    const std::function<void(int, int)>& progress = {});

// The output folder refused before anything is written; the message names the folder (and the foreign entry).
class OutputFolderError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Makes dir ready for writeTumFolder. A missing or empty folder is fine. A non-empty one is refused (a typo
// must not overwrite a recorded sequence's lists), unless `replace_own` and the folder holds only what
// writeTumFolder writes, its rgb.txt marked as a synthetic scene's: then those entries are removed, so no
// frame of the old sequence is left behind. Throws OutputFolderError.
void prepareTumFolder(const std::string& dir, bool replace_own);

}  // namespace bmp::capture

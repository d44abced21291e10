#pragma once
// Writes a synthetic sequence as a TUM-format folder, so it can be replayed like any recorded dataset.
#include <functional>
#include <string>

#include "capture/synthetic_scene.hpp"

namespace bmp::capture {

// Creates dir with rgb/, depth/ (16-bit PNG), mask/ (8-bit PNG, 255 on moving objects), rgb.txt, depth.txt
// and groundtruth.txt; files are named by stamp ("1000.033333.png"). `progress`, when set, is called after
// each frame with (frames done, total). Throws std::runtime_error when a file cannot be written.
void writeTumFolder(const SyntheticScene& scene, const std::string& dir,
                    const std::function<void(int, int)>& progress = {});

}  // namespace bmp::capture

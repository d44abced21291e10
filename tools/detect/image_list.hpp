#pragma once
// Which images a tool should read: one file, every PNG/JPEG of a folder, or the colour frames of a TUM
// sequence folder (rgb.txt).
#include <stdexcept>
#include <string>
#include <vector>

namespace bmp::detect_tools {

struct ImageEntry {
  std::string path;
  std::string name;    // file stem, used for output names
  double stamp = 0.0;  // seconds, from rgb.txt; 0 otherwise
};

// Throws std::runtime_error naming the path when it does not exist, holds no images, or rgb.txt has a
// malformed line.
std::vector<ImageEntry> listImages(const std::string& input);

}  // namespace bmp::detect_tools

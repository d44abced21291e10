#pragma once
// Which images a tool should read: one file, every PNG/JPEG of a folder, or the colour frames of a TUM
// sequence folder (rgb.txt); and one of them read as the detector's input.
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "detector/detection_worker.hpp"

namespace bmp::detect_tools {

struct ImageEntry {
  std::string path;
  std::string name;    // file stem, used for output names
  double stamp = 0.0;  // seconds, from rgb.txt; 0 otherwise
};

// Throws std::runtime_error naming the path when it does not exist, holds no images, or rgb.txt has a
// malformed line.
std::vector<ImageEntry> listImages(const std::string& input);

// The file's bytes as a frame for processFrame, not decoded (decoding is part of the detector's time).
// Throws ImageError when the file is unreadable or not a PNG/JPEG.
detector::FrameJob loadFrameJob(const std::string& path, int64_t seq = 0);

}  // namespace bmp::detect_tools

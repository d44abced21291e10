#pragma once
// Which camera file describes a TUM-format folder.
#include <string>

namespace bmp::capture {

// <dir>/camera.yaml if the folder has one; else by the sequence name: "bonn" -> bonn.yaml,
// "freiburg1"/"fr1" -> tum_fr1.yaml (likewise 2 and 3). Returns "" when nothing fits.
std::string cameraFileFor(const std::string& sequence_dir, const std::string& camera_config_dir);

}  // namespace bmp::capture

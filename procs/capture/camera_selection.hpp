#pragma once
// Which camera file describes a TUM-format folder, and the camera it holds.
#include <string>

#include "bmp/common/camera_model.hpp"

namespace bmp::capture {

// <dir>/camera.yaml if the folder has one; else by the folder's own name (not its parents'): "bonn" ->
// bonn.yaml, "freiburg1"/"fr1" -> tum_fr1.yaml (likewise 2 and 3). Returns "" when nothing fits.
std::string cameraFileFor(const std::string& sequence_dir, const std::string& camera_config_dir);

struct SequenceCamera {
  CameraIntrinsics intrinsics;
  std::string file;       // where it was read from
  std::string chosen_by;  // how: "--camera", the folder's camera.yaml, or guessed from its name (for the log)
};

// The camera of a TUM folder: from camera_file when not empty, else as cameraFileFor chooses. Throws
// SequenceError when the folder does not exist, ConfigError naming the folder when nothing fits, and the
// file and key when the file is wrong.
SequenceCamera selectCamera(const std::string& sequence_dir, const std::string& camera_file,
                            const std::string& camera_config_dir);

}  // namespace bmp::capture

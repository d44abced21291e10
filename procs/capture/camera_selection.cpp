#include "capture/camera_selection.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "bmp/common/camera_config.hpp"
#include "bmp/common/config.hpp"
#include "capture/tum_sequence.hpp"

namespace bmp::capture {

std::string cameraFileFor(const std::string& sequence_dir, const std::string& camera_config_dir) {
  namespace fs = std::filesystem;
  if (fs::is_regular_file(fs::path(sequence_dir) / "camera.yaml"))
    return (fs::path(sequence_dir) / "camera.yaml").string();
  // The folder's own name only: a parent such as ~/bonn_tests/ must not choose the camera of its recordings.
  fs::path folder = fs::absolute(sequence_dir).lexically_normal();
  if (folder.filename().empty()) folder = folder.parent_path();  // "dir/"
  std::string name = folder.filename().string();
  std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return std::tolower(c); });
  const auto pick = [&](const char* file) { return (fs::path(camera_config_dir) / file).string(); };
  if (name.find("bonn") != std::string::npos) return pick("bonn.yaml");
  if (name.find("freiburg1") != std::string::npos || name.find("fr1") != std::string::npos)
    return pick("tum_fr1.yaml");
  if (name.find("freiburg2") != std::string::npos || name.find("fr2") != std::string::npos)
    return pick("tum_fr2.yaml");
  if (name.find("freiburg3") != std::string::npos || name.find("fr3") != std::string::npos)
    return pick("tum_fr3.yaml");
  return "";
}

SequenceCamera selectCamera(const std::string& sequence_dir, const std::string& camera_file,
                            const std::string& camera_config_dir) {
  // The folder first: a mistyped folder is "no such folder", not a camera the folder's name cannot tell.
  if (!std::filesystem::is_directory(sequence_dir))
    throw SequenceError(sequence_dir + ": no such sequence folder");
  SequenceCamera out;
  out.file = camera_file.empty() ? cameraFileFor(sequence_dir, camera_config_dir) : camera_file;
  // How, read off the choice: cameraFileFor names the folder's camera.yaml as this path when it took it.
  if (!camera_file.empty())
    out.chosen_by = "--camera";
  else if (out.file == (std::filesystem::path(sequence_dir) / "camera.yaml").string())
    out.chosen_by = "the folder's camera.yaml";
  else
    out.chosen_by = "guessed from the folder's name; pass --camera FILE if another camera recorded it";
  if (out.file.empty())
    throw ConfigError(sequence_dir +
                      ": cannot tell which camera recorded this folder; pass --camera FILE "
                      "(see config/cameras/) or put a camera.yaml in the folder");
  const Config config = Config::fromFile(out.file);
  out.intrinsics = cameraFromConfig(config.section("camera"));
  config.finish();
  return out;
}

}  // namespace bmp::capture

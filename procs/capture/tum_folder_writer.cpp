#include "capture/tum_folder_writer.hpp"

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include <opencv2/imgcodecs.hpp>

#include "bmp/common/tum_trajectory.hpp"

namespace bmp::capture {
namespace {

namespace fs = std::filesystem;

// rgb.txt's second line starts with this: how --overwrite tells a folder bmp-synth wrote from a recording.
constexpr const char* kSyntheticListMark = "# synthetic scene";
constexpr std::array<const char*, 4> kOwnFiles = {"rgb.txt", "depth.txt", "groundtruth.txt", "camera.yaml"};
constexpr std::array<const char*, 3> kOwnFolders = {"rgb", "depth", "mask"};

template <std::size_t N>
bool listed(const std::array<const char*, N>& names, const std::string& name) {
  return std::any_of(names.begin(), names.end(), [&](const char* n) { return name == n; });
}

bool writtenBySynth(const fs::path& dir) {
  std::ifstream in(dir / "rgb.txt");
  std::string line;
  for (int i = 0; i < 3 && std::getline(in, line); ++i)
    if (line.rfind(kSyntheticListMark, 0) == 0) return true;
  return false;
}

// The first entry writeTumFolder would not have written, "" when none. Symbolic links count as foreign:
// removing through them could reach another folder.
std::string foreignEntry(const fs::path& dir) {
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (entry.is_symlink()) return entry.path().string();
    if (entry.is_regular_file() && listed(kOwnFiles, name)) continue;
    if (!entry.is_directory() || !listed(kOwnFolders, name)) return entry.path().string();
    for (const auto& image : fs::directory_iterator(entry.path()))
      if (image.is_symlink() || !image.is_regular_file() || image.path().extension() != ".png")
        return image.path().string();
  }
  return "";
}

std::string stampName(double stamp) {
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "%.6f", stamp);
  return buffer;
}

void writePng(const std::string& path, const cv::Mat& image) {
  if (!cv::imwrite(path, image, {cv::IMWRITE_PNG_COMPRESSION, 1}))
    throw std::runtime_error(path + ": cannot write image");
}

// bmp-capture and tum2lcm pick up DIR/camera.yaml, so the folder plays without --camera.
void writeCameraYaml(const std::string& path, const CameraIntrinsics& k) {
  std::ofstream out(path);
  out << "# Camera of the synthetic sequence in this folder (written by bmp-synth).\ncamera:\n"
      << "  width: " << k.width << "\n  height: " << k.height << "\n  fx: " << k.fx << "\n  fy: " << k.fy
      << "\n  cx: " << k.cx << "\n  cy: " << k.cy << "\n  distortion: [0.0, 0.0, 0.0, 0.0, 0.0]\n"
      << "  depth_scale: " << k.depth_scale << "\n";
  if (!out) throw std::runtime_error(path + ": cannot write camera file");
}

}  // namespace

void writeTumFolder(const SyntheticScene& scene, const std::string& dir,
                    const std::function<void(int, int)>& progress) {
  for (const char* sub : kOwnFolders) fs::create_directories(fs::path(dir) / sub);
  std::ofstream rgb_list(fs::path(dir) / "rgb.txt");
  std::ofstream depth_list(fs::path(dir) / "depth.txt");
  if (!rgb_list || !depth_list) throw std::runtime_error(dir + ": cannot write rgb.txt / depth.txt");
  rgb_list << "# color images\n"
           << kSyntheticListMark << ", seed " << scene.config().seed << "\n# timestamp filename\n";
  depth_list << "# depth maps\n"
             << kSyntheticListMark << ", seed " << scene.config().seed << "\n# timestamp filename\n";
  for (int i = 0; i < scene.numFrames(); ++i) {
    const SyntheticFrame f = scene.render(i);
    const std::string name = stampName(f.stamp);
    writePng(dir + "/rgb/" + name + ".png", f.bgr);
    writePng(dir + "/depth/" + name + ".png", f.depth);
    writePng(dir + "/mask/" + name + ".png", f.mask);
    rgb_list << name << " rgb/" << name << ".png\n";
    depth_list << name << " depth/" << name << ".png\n";
    if (progress) progress(i + 1, scene.numFrames());
  }
  if (!rgb_list || !depth_list) throw std::runtime_error(dir + ": writing rgb.txt / depth.txt failed");
  writeTumTrajectory(dir + "/groundtruth.txt", scene.groundTruth());
  writeCameraYaml(dir + "/camera.yaml", scene.camera());
}

void prepareTumFolder(const std::string& dir, bool replace_own) {
  const fs::path root(dir);
  if (!fs::exists(root)) return;
  if (!fs::is_directory(root)) throw OutputFolderError(dir + ": exists and is not a folder");
  if (fs::is_empty(root)) return;
  if (!replace_own)
    throw OutputFolderError(dir +
                            ": output folder is not empty; give a new or empty folder, or --overwrite to "
                            "replace a sequence bmp-synth wrote there");
  if (!writtenBySynth(root))
    throw OutputFolderError(dir + ": not replaced: its rgb.txt is missing or not one bmp-synth wrote");
  const std::string foreign = foreignEntry(root);
  if (!foreign.empty())
    throw OutputFolderError(dir + ": not replaced: " + foreign + " is not something bmp-synth writes");
  for (const char* name : kOwnFiles) fs::remove(root / name);
  for (const char* name : kOwnFolders) fs::remove_all(root / name);
}

}  // namespace bmp::capture

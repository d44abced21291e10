#include "capture/tum_folder_writer.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include <opencv2/imgcodecs.hpp>

#include "bmp/common/tum_trajectory.hpp"

namespace bmp::capture {
namespace {

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
  namespace fs = std::filesystem;
  for (const char* sub : {"rgb", "depth", "mask"}) fs::create_directories(fs::path(dir) / sub);
  std::ofstream rgb_list(fs::path(dir) / "rgb.txt");
  std::ofstream depth_list(fs::path(dir) / "depth.txt");
  if (!rgb_list || !depth_list) throw std::runtime_error(dir + ": cannot write rgb.txt / depth.txt");
  rgb_list << "# color images\n# synthetic scene, seed " << scene.config().seed << "\n# timestamp filename\n";
  depth_list << "# depth maps\n# synthetic scene, seed " << scene.config().seed << "\n# timestamp filename\n";
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

}  // namespace bmp::capture

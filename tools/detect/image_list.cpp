#include "image_list.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "bmp/common/image_codec.hpp"

namespace fs = std::filesystem;

namespace bmp::detect_tools {

namespace {

bool isImage(const fs::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext == ".png" || ext == ".jpg" || ext == ".jpeg";
}

std::vector<ImageEntry> readRgbTxt(const fs::path& folder) {
  const fs::path list = folder / "rgb.txt";
  std::ifstream in(list);
  if (!in) throw std::runtime_error(list.string() + ": cannot open");
  std::vector<ImageEntry> out;
  int line_no = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_no;
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    ImageEntry e;
    std::string file;
    if (!(fields >> e.stamp >> file))
      throw std::runtime_error(list.string() + ":" + std::to_string(line_no) + ": expected 'stamp file'");
    e.path = (folder / file).string();
    e.name = fs::path(file).stem().string();
    out.push_back(e);
  }
  return out;
}

}  // namespace

std::vector<ImageEntry> listImages(const std::string& input) {
  const fs::path path(input);
  std::vector<ImageEntry> out;
  if (fs::is_regular_file(path)) {
    out.push_back({path.string(), path.stem().string(), 0.0});
  } else if (fs::is_directory(path) && fs::exists(path / "rgb.txt")) {
    out = readRgbTxt(path);
  } else if (fs::is_directory(path)) {
    for (const auto& entry : fs::directory_iterator(path))
      if (entry.is_regular_file() && isImage(entry.path()))
        out.push_back({entry.path().string(), entry.path().stem().string(), 0.0});
    std::sort(out.begin(), out.end(),
              [](const ImageEntry& a, const ImageEntry& b) { return a.path < b.path; });
  } else {
    throw std::runtime_error(input + ": no such file or folder");
  }
  if (out.empty()) throw std::runtime_error(input + ": no PNG or JPEG images found");
  return out;
}

detector::FrameJob loadFrameJob(const std::string& path, int64_t seq) {
  detector::FrameJob job;
  job.seq = seq;
  job.color.data = readFileBytes(path);
  const ImageProbe probe = probeEncodedImage(job.color.data);
  job.color.width = probe.width;
  job.color.height = probe.height;
  job.color.encoding = probe.encoding;
  return job;
}

}  // namespace bmp::detect_tools

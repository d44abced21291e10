#include "image_list.hpp"

#include <algorithm>
#include <filesystem>

#include "bmp/common/image_codec.hpp"
#include "bmp/common/tum_text_list.hpp"

namespace fs = std::filesystem;

namespace bmp::detect_tools {

namespace {

bool isImage(const fs::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext == ".png" || ext == ".jpg" || ext == ".jpeg";
}

// rgb.txt read as bmp-capture reads it (the common TUM list parser), so both accept the same folders.
std::vector<ImageEntry> readRgbTxt(const fs::path& folder) {
  std::vector<ImageEntry> out;
  for (const auto& record :
       readTumTextList((folder / "rgb.txt").string(), {"list file", "timestamp filename", 1, false})) {
    const std::string& file = record.fields[0];
    out.push_back({(folder / file).string(), fs::path(file).stem().string(), record.stamp});
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

#include "mapper/grid_pair.hpp"

#include <cstdint>
#include <filesystem>

#include "bmp/common/atomic_file.hpp"
#include "mapper/grid_files.hpp"

namespace bmp::mapper {

namespace {

namespace fs = std::filesystem;

constexpr const char* kPrefix = "occupancy.";
constexpr const char* kSuffix = ".pgm";

// N of occupancy.N.pgm, or 0 for any other name.
uint64_t numberOf(const std::string& name) {
  const std::string prefix = kPrefix, suffix = kSuffix;
  if (name.size() <= prefix.size() + suffix.size() || name.compare(0, prefix.size(), prefix) != 0 ||
      name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0)
    return 0;
  const std::string digits = name.substr(prefix.size(), name.size() - prefix.size() - suffix.size());
  if (digits.size() > 18 || digits.find_first_not_of("0123456789") != std::string::npos) return 0;
  return std::stoull(digits);
}

std::vector<std::pair<uint64_t, fs::path>> numberedImages(const fs::path& dir) {
  std::vector<std::pair<uint64_t, fs::path>> out;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec))
    if (const uint64_t n = numberOf(entry.path().filename().string()); n > 0)
      out.emplace_back(n, entry.path());
  return out;
}

}  // namespace

std::vector<std::string> writeGridPair(const std::string& dir_name, const OccupancyGrid2D& grid) {
  const fs::path dir(dir_name);
  const auto existing = numberedImages(dir);
  uint64_t last = 0;
  for (const auto& [n, path] : existing) last = std::max(last, n);
  const uint64_t number = last + 1;
  const std::string image_name = kPrefix + std::to_string(number) + kSuffix;
  const std::string pgm = encodePgm(grid);
  std::vector<std::string> written;
  const auto put = [&](const std::string& name, const std::string& content) {
    const std::string path = (dir / name).string();
    writeFileAtomically(path, content);
    written.push_back(path);
  };
  put(image_name, pgm);  // first: the YAML must never name an image that is not all there
  put("occupancy.pgm", pgm);
  put("occupancy.yaml", encodeMapYaml(grid, image_name));
  for (const auto& [n, path] : existing) {
    std::error_code ec;  // a file already gone is fine: nothing depends on it
    if (n < last) fs::remove(path, ec);
  }
  return written;
}

}  // namespace bmp::mapper

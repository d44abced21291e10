#include "launcher/run_folder.hpp"

#include <filesystem>
#include <stdexcept>

namespace bmp::launcher {

std::vector<std::string> setAsideEarlierResults(const std::string& out_dir) {
  namespace fs = std::filesystem;
  std::vector<std::string> moved;
  for (const char* name : {"groundtruth.txt", "eval.json", "summary.json", "plots"}) {
    const fs::path earlier = fs::path(out_dir) / name;
    std::error_code ec;
    if (!fs::exists(fs::symlink_status(earlier, ec))) continue;
    const fs::path kept = fs::path(out_dir) / (std::string(name) + ".prev");
    fs::remove_all(kept, ec);
    if (!ec) fs::rename(earlier, kept, ec);
    if (ec)
      throw std::runtime_error(earlier.string() + ": an earlier run's result that cannot be set aside as " +
                               kept.string() + ": " + ec.message());
    moved.push_back(name);
  }
  return moved;
}

}  // namespace bmp::launcher

#include "launcher/run_folder.hpp"

#include <filesystem>
#include <stdexcept>

#include "bmp/common/arg_parser.hpp"

namespace bmp::launcher {

bool setAsideEarlierRun(const std::string& out_dir) {
  namespace fs = std::filesystem;
  const fs::path out(out_dir);
  std::error_code ec;
  if (!fs::exists(fs::symlink_status(out, ec))) return false;
  if (!fs::is_directory(out, ec)) throw ArgError("bmp-run: --out '" + out_dir + "': not a folder");
  if (fs::is_empty(out, ec)) return false;
  // Only what a run wrote is moved: a user's folder given by mistake (--out ~) must stay as it is.
  if (!fs::is_directory(out / "logs", ec))
    throw ArgError("bmp-run: --out '" + out_dir +
                   "': a folder that is not empty and not an earlier run's (no logs/); give a new or empty "
                   "folder, or an earlier run's");
  const fs::path previous = out / kPreviousRunFolder;
  fs::remove_all(previous, ec);
  if (!ec) fs::create_directory(previous, ec);
  if (ec)
    throw std::runtime_error(previous.string() +
                             ": cannot make the folder for the earlier run: " + ec.message());
  for (const auto& entry : fs::directory_iterator(out)) {
    if (entry.path().filename() == kPreviousRunFolder) continue;
    fs::rename(entry.path(), previous / entry.path().filename(), ec);
    if (ec)
      throw std::runtime_error(entry.path().string() + ": an earlier run's output that cannot be moved to " +
                               previous.string() + ": " + ec.message());
  }
  return true;
}

}  // namespace bmp::launcher

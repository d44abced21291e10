#pragma once
// Files that are either wholly the old version or wholly the new one, for outputs a reader or a crash must
// never see half written (trajectories now; maps later).
#include <stdexcept>
#include <string>

namespace bmp {

class FileWriteError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Writes content to a unique temporary file beside path, syncs it to disk, renames it over path and syncs
// the folder. Throws FileWriteError naming path; the old file is then untouched.
void writeFileAtomically(const std::string& path, const std::string& content);

}  // namespace bmp

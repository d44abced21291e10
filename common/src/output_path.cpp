#include "bmp/common/output_path.hpp"

#include <unistd.h>

#include <filesystem>
#include <system_error>

namespace bmp {

void checkOutputOption(const ArgParser& args, const std::string& option) {
  if (!args.given(option)) return;
  namespace fs = std::filesystem;
  const std::string path = args.value(option);
  const auto refuse = [&](const std::string& why) {
    throw ArgError(args.program() + ": --" + option + " '" + path + "': " + why);
  };
  if (path.empty()) refuse("an empty path");
  std::error_code error;
  const fs::file_status status = fs::status(path, error);
  // Not found is what a new file's path gives; anything else (a name too long, a file used as a folder)
  // is the path's fault.
  if (error && error != std::errc::no_such_file_or_directory) refuse(error.message());
  if (fs::is_directory(status)) refuse("is a folder, not a file");
  fs::path folder = fs::path(path).parent_path();
  if (folder.empty()) folder = ".";
  if (!fs::is_directory(folder, error)) refuse("no such folder " + folder.string());
  // The same test the kernel makes when the file is created: write and search permission on the folder.
  if (::access(folder.c_str(), W_OK | X_OK) != 0) refuse("cannot write in " + folder.string());
}

}  // namespace bmp

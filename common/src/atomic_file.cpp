#include "bmp/common/atomic_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <utility>
#include <vector>

namespace bmp {

namespace {

std::string reason() {
  return std::strerror(errno);
}

// Closes a descriptor once, whatever happens between open and the explicit close.
class Fd {
 public:
  explicit Fd(int fd) : fd_(fd) {}
  ~Fd() {
    if (fd_ >= 0) ::close(fd_);
  }
  Fd(const Fd&) = delete;
  Fd& operator=(const Fd&) = delete;
  int get() const { return fd_; }
  int release() { return std::exchange(fd_, -1); }

 private:
  int fd_;
};

}  // namespace

void writeFileAtomically(const std::string& path, const std::string& content) {
  const std::string what = path + ": cannot write: ";
  std::vector<char> tmp(path.begin(), path.end());
  const std::string suffix = ".tmp.XXXXXX";  // unique: two writers of one path never share a temporary
  tmp.insert(tmp.end(), suffix.begin(), suffix.end());
  tmp.push_back('\0');
  Fd fd(::mkstemp(tmp.data()));
  if (fd.get() < 0) throw FileWriteError(what + reason());
  const std::string tmp_path(tmp.data());
  const auto fail = [&](const std::string& why) {
    ::unlink(tmp_path.c_str());
    throw FileWriteError(what + why);
  };
  for (std::size_t done = 0; done < content.size();) {
    const ssize_t n = ::write(fd.get(), content.data() + done, content.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) fail(reason());
    done += static_cast<std::size_t>(n);
  }
  if (::fchmod(fd.get(), 0644) != 0) fail(reason());  // mkstemp makes 0600; outputs are for everyone
  if (::fsync(fd.get()) != 0) fail(reason());
  if (::close(fd.release()) != 0) fail(reason());
  if (::rename(tmp_path.c_str(), path.c_str()) != 0) fail(reason());
  // The rename itself is durable only once the folder is synced.
  const std::filesystem::path parent = std::filesystem::absolute(path).parent_path();
  Fd dir(::open(parent.c_str(), O_RDONLY | O_DIRECTORY));
  if (dir.get() >= 0) ::fsync(dir.get());
}

}  // namespace bmp

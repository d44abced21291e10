#include "launcher/output_relay.hpp"

#include <poll.h>
#include <unistd.h>

#include <cstdio>

namespace bmp::launcher {

void OutputRelay::follow(int fd, const std::string& name, const std::string& log_path, bool echo_all) {
  auto s = std::make_unique<Stream>();
  s->fd = fd;
  s->name = name;
  s->log.open(log_path);
  s->echo_all = echo_all;
  streams_.push_back(std::move(s));
}

void OutputRelay::emit(Stream& s, const std::string& line) {
  s.log << line << '\n';
  s.log.flush();
  const bool important = line.find("[W]") != std::string::npos || line.find("[E]") != std::string::npos;
  if (s.echo_all || important) std::fprintf(stderr, "%-13s| %s\n", s.name.c_str(), line.c_str());
}

bool OutputRelay::pump(int timeout_ms) {
  std::vector<pollfd> fds;
  std::vector<Stream*> owners;
  for (auto& s : streams_) {
    if (!s->open) continue;
    fds.push_back({s->fd, POLLIN, 0});
    owners.push_back(s.get());
  }
  if (fds.empty()) return false;
  if (::poll(fds.data(), fds.size(), timeout_ms) <= 0) return true;
  char buffer[8192];
  for (std::size_t i = 0; i < fds.size(); ++i) {
    if (!(fds[i].revents & (POLLIN | POLLHUP | POLLERR))) continue;
    Stream& s = *owners[i];
    const ssize_t n = ::read(s.fd, buffer, sizeof(buffer));
    if (n <= 0) {
      if (!s.partial.empty()) emit(s, s.partial);
      s.partial.clear();
      s.open = false;
      continue;
    }
    s.partial.append(buffer, static_cast<std::size_t>(n));
    for (std::size_t pos; (pos = s.partial.find('\n')) != std::string::npos;) {
      emit(s, s.partial.substr(0, pos));
      s.partial.erase(0, pos + 1);
    }
  }
  return true;
}

}  // namespace bmp::launcher

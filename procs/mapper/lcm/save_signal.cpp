#include "mapper/lcm/save_signal.hpp"

#include <pthread.h>
#include <sys/signalfd.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstring>
#include <stdexcept>
#include <string>

namespace bmp::mapper {

SaveSignal::SaveSignal() {
  sigset_t set, old;
  sigemptyset(&set);
  sigaddset(&set, SIGUSR1);
  if (pthread_sigmask(SIG_BLOCK, &set, &old) != 0) throw std::runtime_error("cannot block SIGUSR1");
  was_blocked_ = sigismember(&old, SIGUSR1) == 1;
  fd_ = signalfd(-1, &set, SFD_NONBLOCK | SFD_CLOEXEC);
  if (fd_ < 0) throw std::runtime_error(std::string("signalfd(SIGUSR1): ") + std::strerror(errno));
}

SaveSignal::~SaveSignal() {
  pending();  // a signal still pending when unblocked would take its default action: ending the process
  ::close(fd_);
  if (!was_blocked_) {
    sigset_t set;
    sigemptyset(&set);
    sigaddset(&set, SIGUSR1);
    pthread_sigmask(SIG_UNBLOCK, &set, nullptr);
  }
}

bool SaveSignal::pending() {
  bool any = false;
  signalfd_siginfo info;
  while (::read(fd_, &info, sizeof(info)) == static_cast<ssize_t>(sizeof(info))) any = true;
  return any;
}

}  // namespace bmp::mapper

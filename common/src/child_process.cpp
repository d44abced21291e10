#include "bmp/common/child_process.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <thread>

namespace bmp {

ChildProcess::ChildProcess(std::vector<std::string> argv, Output output, const std::string& output_path,
                           const std::vector<std::string>& extra_env) {
  if (argv.empty()) throw std::runtime_error("ChildProcess: empty command");
  name_ = std::filesystem::path(argv[0]).filename().string();
  int out_fd = -1;
  int pipe_fds[2] = {-1, -1};
  if (output == Output::kFile) {
    out_fd = ::open(output_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (out_fd < 0) throw std::runtime_error(output_path + ": cannot open log file: " + std::strerror(errno));
  } else if (output == Output::kPipe) {
    if (::pipe2(pipe_fds, O_CLOEXEC) != 0)
      throw std::runtime_error(std::string("pipe: ") + std::strerror(errno));
    out_fd = pipe_fds[1];
  }
  std::vector<char*> args;
  for (auto& a : argv) args.push_back(a.data());
  args.push_back(nullptr);
  std::vector<std::string> env_copy = extra_env;

  const pid_t parent = ::getpid();
  pid_ = ::fork();
  if (pid_ < 0) {
    const std::string why = std::strerror(errno);
    if (out_fd >= 0) ::close(out_fd);  // the pipe's write end, or the log file
    if (pipe_fds[0] >= 0) ::close(pipe_fds[0]);
    throw std::runtime_error("fork: " + why);
  }
  if (pid_ == 0) {
    // If the parent dies (a launcher killed with SIGKILL), the child is asked to stop as by Ctrl-C and
    // writes what it owes, instead of running on as an orphan. And a closed output pipe must not kill it
    // before that: SIGPIPE stays ignored across exec, so writes fail with EPIPE instead.
    ::prctl(PR_SET_PDEATHSIG, SIGTERM);
    if (::getppid() != parent) ::raise(SIGTERM);  // the parent died before prctl took effect
    ::signal(SIGPIPE, SIG_IGN);
    if (out_fd >= 0) {
      ::dup2(out_fd, STDOUT_FILENO);
      ::dup2(out_fd, STDERR_FILENO);
    }
    for (auto& e : env_copy) ::putenv(e.data());
    ::execv(args[0], args.data());
    const std::string message = std::string("cannot execute ") + args[0] + ": " + std::strerror(errno) + "\n";
    (void)!::write(STDERR_FILENO, message.data(), message.size());
    ::_exit(127);
  }
  if (output == Output::kPipe) {
    ::close(pipe_fds[1]);
    pipe_fd_ = pipe_fds[0];
  } else if (out_fd >= 0) {
    ::close(out_fd);
  }
}

ChildProcess::~ChildProcess() {
  if (pid_ > 0 && !status_) {
    ::kill(pid_, SIGKILL);
    int raw = 0;
    ::waitpid(pid_, &raw, 0);
  }
  if (pipe_fd_ >= 0) ::close(pipe_fd_);
}

void ChildProcess::reap(int raw_status) {
  if (WIFEXITED(raw_status)) {
    status_ = WEXITSTATUS(raw_status);
  } else if (WIFSIGNALED(raw_status)) {
    status_ = 128 + WTERMSIG(raw_status);
    killed_by_signal_ = true;
  }
}

bool ChildProcess::running() {
  if (status_) return false;
  int raw = 0;
  const pid_t r = ::waitpid(pid_, &raw, WNOHANG);
  if (r == pid_) reap(raw);
  return !status_;
}

void ChildProcess::signal(int signo) {
  if (!status_) ::kill(pid_, signo);
}

std::optional<int> ChildProcess::wait(double timeout_s) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (running()) {
    if (std::chrono::steady_clock::now() >= deadline) return std::nullopt;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return status_;
}

int ChildProcess::stop(double grace_s) {
  if (!running()) return *status_;
  signal(SIGINT);
  if (auto s = wait(grace_s)) return *s;
  signal(SIGKILL);
  wait(5.0);
  return status_.value_or(128 + SIGKILL);
}

}  // namespace bmp

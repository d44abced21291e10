#pragma once
// A child process owned by an object: started with fork/exec, its output sent to a file or a pipe, and
// killed on destruction if it is still running, so a failing test or launcher never leaves orphans. If the
// parent itself is killed, the child receives SIGTERM (parent-death signal) and stops cleanly.
#include <sys/types.h>

#include <optional>
#include <string>
#include <vector>

namespace bmp {

class ChildProcess {
 public:
  enum class Output { kInherit, kFile, kPipe };

  // argv[0] is the executable path. With kFile, stdout and stderr go to output_path (truncated);
  // with kPipe, both go to a pipe read through outputFd(). Throws std::runtime_error if it cannot start.
  ChildProcess(std::vector<std::string> argv, Output output = Output::kInherit,
               const std::string& output_path = "", const std::vector<std::string>& extra_env = {});
  ~ChildProcess();
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  pid_t pid() const { return pid_; }
  const std::string& name() const { return name_; }
  int outputFd() const { return pipe_fd_; }
  // Non-blocking: true while the process has not been reaped.
  bool running();
  void signal(int signo);
  // Waits up to timeout_s for the exit; returns the exit status if it ended.
  std::optional<int> wait(double timeout_s);
  // SIGINT, then SIGKILL if it has not ended within grace_s. Returns the exit status.
  int stop(double grace_s);
  // Exit code (0-255), or 128 + signal number when killed by a signal; nullopt while running.
  std::optional<int> exitStatus() const { return status_; }
  bool killedBySignal() const { return killed_by_signal_; }

 private:
  void reap(int raw_status);
  std::string name_;
  pid_t pid_ = -1;
  int pipe_fd_ = -1;
  std::optional<int> status_;
  bool killed_by_signal_ = false;
};

}  // namespace bmp

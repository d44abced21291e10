#include <gtest/gtest.h>
#include <unistd.h>

#include <sys/wait.h>

#include <chrono>
#include <csignal>
#include <fstream>
#include <thread>

#include "bmp/common/child_process.hpp"

namespace bmp {
namespace {

TEST(ChildProcess, ExitCodeAndPipedOutput) {
  ChildProcess child({"/bin/sh", "-c", "echo hello; exit 3"}, ChildProcess::Output::kPipe);
  std::string out;
  char buf[256];
  for (ssize_t n; (n = ::read(child.outputFd(), buf, sizeof(buf))) > 0;)
    out.append(buf, static_cast<size_t>(n));
  EXPECT_EQ(child.wait(5.0), 3);
  EXPECT_EQ(out, "hello\n");
}

TEST(ChildProcess, StopEscalatesToKill) {
  // The shell ignores SIGINT, so stop() must fall back to SIGKILL.
  ChildProcess child({"/bin/sh", "-c", "trap '' INT; echo ready; while true; do sleep 0.05; done"},
                     ChildProcess::Output::kPipe);
  EXPECT_TRUE(child.running());
  // The shell says when its trap is installed: a signal before that would end it with SIGINT.
  char c = 0;
  ASSERT_EQ(::read(child.outputFd(), &c, 1), 1);
  EXPECT_EQ(c, 'r');
  EXPECT_EQ(child.stop(0.3), 128 + SIGKILL);
  EXPECT_TRUE(child.killedBySignal());
}

TEST(ChildProcess, MissingExecutableExits127) {
  ChildProcess child({"/nonexistent/binary"}, ChildProcess::Output::kPipe);
  EXPECT_EQ(child.wait(5.0), 127);
}

// A launcher killed outright must not leave its children running: they get SIGTERM (and stop cleanly).
TEST(ChildProcess, ChildStopsWhenItsParentDies) {
  int fds[2];
  ASSERT_EQ(::pipe(fds), 0);
  const pid_t middle = ::fork();
  ASSERT_GE(middle, 0);
  if (middle == 0) {
    auto* child = new ChildProcess({"/bin/sleep", "60"});  // never destroyed: the parent just dies
    const pid_t pid = child->pid();
    (void)!::write(fds[1], &pid, sizeof(pid));
    ::_exit(0);
  }
  pid_t grandchild = 0;
  ASSERT_EQ(::read(fds[0], &grandchild, sizeof(grandchild)), static_cast<ssize_t>(sizeof(grandchild)));
  ::close(fds[0]);
  ::close(fds[1]);
  int raw = 0;
  ::waitpid(middle, &raw, 0);
  const auto alive = [grandchild] {
    std::ifstream stat("/proc/" + std::to_string(grandchild) + "/stat");
    std::string pid, comm, state;
    return static_cast<bool>(stat >> pid >> comm >> state) && state != "Z";
  };
  for (int i = 0; i < 100 && alive(); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  EXPECT_FALSE(alive()) << "sleep " << grandchild << " outlived its parent";
  if (alive()) ::kill(grandchild, SIGKILL);
}

}  // namespace
}  // namespace bmp

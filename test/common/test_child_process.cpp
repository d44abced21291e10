#include <gtest/gtest.h>
#include <unistd.h>

#include <csignal>

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
  ChildProcess child({"/bin/sh", "-c", "trap '' INT; while true; do sleep 0.05; done"});
  EXPECT_TRUE(child.running());
  ::usleep(300000);  // let the shell install its trap before the signal arrives
  EXPECT_EQ(child.stop(0.3), 128 + SIGKILL);
  EXPECT_TRUE(child.killedBySignal());
}

TEST(ChildProcess, MissingExecutableExits127) {
  ChildProcess child({"/nonexistent/binary"}, ChildProcess::Output::kPipe);
  EXPECT_EQ(child.wait(5.0), 127);
}

}  // namespace
}  // namespace bmp

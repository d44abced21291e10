// --wait-for's bookkeeping counts distinct processes (name and instance), not names; and the LCM wait
// around it, with real StatusReporters over udpm://.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <memory>
#include <thread>

#include "bmp/lcm/wait_for_processes.hpp"
#include "lcm_url.hpp"

namespace bmp {
namespace {

TEST(ProcessWaitList, EachDistinctInstanceSatisfiesOneEntry) {
  ProcessWaitList wait({"bmp-tracker", "bmp-tracker", "bmp-detector"});
  EXPECT_FALSE(wait.satisfied());
  EXPECT_EQ(wait.missing(), "1 more bmp-detector, 2 more bmp-tracker");
  EXPECT_TRUE(wait.heard("bmp-tracker", 11));
  // The same tracker's next heartbeat is not a second tracker: the race the old name set lost.
  EXPECT_FALSE(wait.heard("bmp-tracker", 11));
  EXPECT_EQ(wait.missing(), "1 more bmp-detector, 1 more bmp-tracker");
  EXPECT_TRUE(wait.heard("bmp-detector", 11));  // instances are per name: no clash with the tracker's
  EXPECT_FALSE(wait.satisfied());
  EXPECT_TRUE(wait.heard("bmp-tracker", 12));
  EXPECT_TRUE(wait.satisfied());
  EXPECT_EQ(wait.missing(), "");
  EXPECT_FALSE(wait.heard("bmp-tracker", 13));  // more than asked for changes nothing
  EXPECT_TRUE(wait.satisfied());
}

TEST(ProcessWaitList, OtherNamesAndAnEmptyListCount) {
  ProcessWaitList wait({"a"});
  EXPECT_FALSE(wait.heard("b", 1));
  EXPECT_FALSE(wait.heard("bmp-capture", 2));
  EXPECT_FALSE(wait.satisfied());
  EXPECT_TRUE(ProcessWaitList({}).satisfied());
}

// Processes named `name` sending heartbeats every 20 ms from a thread of their own, as real ones would: each
// StatusReporter is one process start with its own instance.
class Heartbeats {
 public:
  Heartbeats(const std::string& url, const std::string& name, int processes)
      : thread_([this, url, name, processes] {
          LcmNode lcm(url);
          std::vector<std::unique_ptr<StatusReporter>> reporters;
          for (int i = 0; i < processes; ++i)
            reporters.push_back(std::make_unique<StatusReporter>(lcm, name));
          while (!done_) {
            for (auto& r : reporters) r->tick(true);
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
          }
        }) {}
  ~Heartbeats() {
    done_ = true;
    thread_.join();
  }

 private:
  std::atomic<bool> done_{false};
  std::thread thread_;
};

TEST(StatusReporter, EveryReporterIsAnInstanceOfItsOwn) {
  LcmNode lcm("memq://");
  const StatusReporter a(lcm, "x"), b(lcm, "x");
  EXPECT_NE(a.instance(), 0);
  EXPECT_NE(a.instance(), b.instance());
}

TEST(WaitForProcesses, CountsProcessesNotHeartbeats) {
  const std::string url = test::uniqueLcmUrl(0);
  LcmNode lcm(url);
  StopSignal stop;
  const Heartbeats two(url, "bmp-tracker", 2);
  EXPECT_TRUE(waitForProcesses(lcm, stop, {"bmp-tracker", "bmp-tracker"}, 10.0));
  // Two trackers, each heard many times, never make three.
  try {
    waitForProcesses(lcm, stop, {"bmp-tracker", "bmp-tracker", "bmp-tracker"}, 0.5);
    FAIL() << "two trackers released a wait for three";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "no heartbeat from 1 more bmp-tracker within 0.5 s");
  }
  EXPECT_TRUE(waitForProcesses(lcm, stop, {}, 0.1));
}

TEST(WaitForProcesses, StopRequestEndsTheWait) {
  LcmNode lcm("memq://");
  StopSignal stop;
  stop.request();
  EXPECT_FALSE(waitForProcesses(lcm, stop, {"never"}, 5.0, "STATUS"));
}

}  // namespace
}  // namespace bmp

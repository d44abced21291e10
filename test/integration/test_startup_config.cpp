// The start-up configuration each process reports: the values in use, command-line overrides included, and
// --print-config printing them without starting.
#include <gtest/gtest.h>

#include <string>

#include "integration_support.hpp"

namespace bmp {
namespace {

using test::binPath;
using test::Outcome;
using test::runCommand;

// bmp-run starts capture with --mode lockstep and --ack-channels: the log used to show the file's realtime
// and [SLAM_POSE] though capture played in lockstep.
TEST(StartupConfig, CaptureShowsItsOptionsNotTheFileValues) {
  const Outcome o = runCommand(
      "capture_print_config",
      {binPath("bmp-capture"), "--config", test::sourceDir() + "/config/capture.yaml", "--mode", "lockstep",
       "--speed", "2", "--ack-channels", "SLAM_POSE,DETECTIONS", "--print-config", "--lcm-url", "memq://"},
      30);
  ASSERT_EQ(o.status, 0) << o.output;  // printed and exited; without --print-config it would play
  EXPECT_NE(o.output.find("capture.mode = lockstep (--mode)"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("capture.speed = 2 (--speed)"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("capture.ack_channels = [SLAM_POSE, DETECTIONS] (--ack-channels)"),
            std::string::npos)
      << o.output;
  EXPECT_EQ(o.output.find("capture.mode = realtime"), std::string::npos) << o.output;
  EXPECT_EQ(o.output.find("playing"), std::string::npos) << o.output;
}

TEST(StartupConfig, TrackerShowsItsDynamicModeOption) {
  const Outcome o =
      runCommand("tracker_print_config",
                 {binPath("bmp-tracker"), "--config", test::sourceDir() + "/config/tracker.yaml",
                  "--dynamic-mode", "paper", "--print-config", "--lcm-url", "memq://"},
                 30);
  ASSERT_EQ(o.status, 0) << o.output;
  EXPECT_NE(o.output.find("tracker.dynamic.mode = paper (--dynamic-mode)"), std::string::npos) << o.output;
  EXPECT_EQ(o.output.find("tracker.dynamic.mode = geometric"), std::string::npos) << o.output;
}

}  // namespace
}  // namespace bmp

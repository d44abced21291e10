// bmp-capture's settings: defaults, command-line overrides, and every rule naming where the bad value is.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "bmp/common/config.hpp"
#include "capture/capture_settings.hpp"

namespace bmp::capture {
namespace {

const char* const kFile = "/etc/bmp/capture.yaml";  // only named in messages

struct Parsed {
  ArgParser args{"bmp-capture", "test"};
  Config config;
  explicit Parsed(const std::string& yaml, std::vector<const char*> argv = {})
      : config(Config::fromString(yaml, kFile)) {
    addCaptureOptions(args);
    argv.insert(argv.begin(), "bmp-capture");
    args.parse(static_cast<int>(argv.size()), argv.data());
  }
  CaptureSettings read() const { return readCaptureSettings(config.section("capture"), args, "/cfg"); }
};

// The message of the ConfigError reading throws, or "" when it does not.
std::string configError(const std::string& yaml, std::vector<const char*> argv = {}) {
  const Parsed p(yaml, std::move(argv));
  try {
    p.read();
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(CaptureSettings, DefaultsWithoutFileOrOptions) {
  const CaptureSettings s = Parsed("{}").read();
  EXPECT_EQ(s.player.channel, "RGBD_FRAME");
  EXPECT_EQ(s.player.ack_channels, std::vector<std::string>{"SLAM_POSE"});
  EXPECT_EQ(s.player.mode, RateMode::kRealtime);
  EXPECT_DOUBLE_EQ(s.player.speed, 1.0);
  EXPECT_EQ(s.verify, VerifyMode::kHeader);
  EXPECT_EQ(s.synthetic_config, "/cfg/synthetic.yaml");
  EXPECT_EQ(s.cameras_dir, "/cfg/cameras");
  EXPECT_EQ(s.selection.every, 1);
  EXPECT_TRUE(s.wait_for.empty());
  EXPECT_TRUE(s.dataset.empty());
}

TEST(CaptureSettings, CommandLineWinsOverTheFile) {
  const Parsed p("capture:\n  mode: fast\n  speed: 2.0\n  verify: header\n  ack_channels: [A]\n",
                 {"--mode", "lockstep", "--speed", "3", "--verify", "decode", "--ack-channels", "X,,Y",
                  "--synthetic-config", "my.yaml", "--every", "2", "--wait-for", "a,a,b"});
  const CaptureSettings s = p.read();
  EXPECT_EQ(s.player.mode, RateMode::kLockstep);
  EXPECT_DOUBLE_EQ(s.player.speed, 3.0);
  EXPECT_EQ(s.verify, VerifyMode::kDecode);
  EXPECT_EQ(s.player.ack_channels, (std::vector<std::string>{"X", "Y"}));
  EXPECT_EQ(s.synthetic_config, "my.yaml");
  EXPECT_EQ(s.selection.every, 2);
  // A repeated name asks for that many distinct processes.
  EXPECT_EQ(s.wait_for, (std::vector<std::string>{"a", "a", "b"}));
  p.config.finish();  // every key was read, although overridden
}

TEST(CaptureSettings, WrongFileValuesNameFileAndKey) {
  const struct {
    const char* yaml;
    const char* key;
  } cases[] = {
      {"capture:\n  speed: 0\n", "capture.speed"},
      {"capture:\n  speed: -1.5\n", "capture.speed"},
      {"capture:\n  speed: 1.0e-300\n", "capture.speed"},
      {"capture:\n  speed: 1.0e+9\n", "capture.speed"},
      {"capture:\n  lockstep_timeout_s: 0\n", "capture.lockstep_timeout_s"},
      {"capture:\n  progress_every_s: -1\n", "capture.progress_every_s"},
      {"capture:\n  wait_timeout_s: 0\n", "capture.wait_timeout_s"},
      {"capture:\n  max_association_difference_s: 0\n", "capture.max_association_difference_s"},
      {"capture:\n  verify: thorough\n", "capture.verify"},
      {"capture:\n  mode: slow\n", "capture.mode"},
      {"capture:\n  channel: ''\n", "capture.channel"},
      {"capture:\n  mode: lockstep\n  ack_channels: []\n", "capture.ack_channels"},
  };
  for (const auto& c : cases) {
    const std::string message = configError(c.yaml);
    EXPECT_NE(message.find(kFile), std::string::npos) << c.yaml << " -> " << message;
    EXPECT_NE(message.find(std::string("'") + c.key + "'"), std::string::npos) << c.yaml << " -> " << message;
  }
  EXPECT_NE(configError("capture:\n  mode: lockstep\n  ack_channels: []\n").find("needs at least one answer"),
            std::string::npos);
  EXPECT_NE(configError("capture:\n  verify: thorough\n").find("thorough"), std::string::npos);
}

TEST(CaptureSettings, WrongOptionsNameTheOption) {
  const struct {
    std::vector<const char*> argv;
    const char* option;
  } cases[] = {
      {{"--speed", "0"}, "--speed"},
      {{"--mode", "slow"}, "--mode"},
      {{"--verify", "all"}, "--verify"},
      {{"--every", "0"}, "--every"},
      {{"--start", "-3"}, "--start"},
      {{"--end", "-2"}, "--end"},
      {{"--mode", "lockstep", "--ack-channels", ""}, "--ack-channels"},
  };
  for (const auto& c : cases) {
    const Parsed p("{}", c.argv);
    try {
      p.read();
      ADD_FAILURE() << c.option << " accepted";
    } catch (const ArgError& e) {
      EXPECT_NE(std::string(e.what()).find(c.option), std::string::npos) << e.what();
    }
  }
}

// --start 10 --end 5 published nothing and exited 1 with "published 0 frames": the range is refused up
// front, naming both options.
TEST(CaptureSettings, AnEmptyFrameRangeIsRefusedNamingBothOptions) {
  for (const char* end : {"5", "10"}) {
    const Parsed p("{}", {"--start", "10", "--end", end});
    try {
      p.read();
      ADD_FAILURE() << "--end " << end << " accepted";
    } catch (const ArgError& e) {
      EXPECT_NE(std::string(e.what()).find("--end '" + std::string(end) + "'"), std::string::npos)
          << e.what();
      EXPECT_NE(std::string(e.what()).find("--start 10"), std::string::npos) << e.what();
    }
  }
  EXPECT_NO_THROW(Parsed("{}", {"--start", "10", "--end", "11"}).read());
  EXPECT_NO_THROW(Parsed("{}", {"--start", "10"}).read());  // --end -1: to the end
}

TEST(CaptureSettings, LockstepNeedsAnAnswerChannelWhereverModeComesFrom) {
  // The file empties the list, the command line asks for lockstep: the file's key is what is wrong.
  EXPECT_NE(
      configError("capture:\n  ack_channels: []\n", {"--mode", "lockstep"}).find("capture.ack_channels"),
      std::string::npos);
  EXPECT_EQ(configError("capture:\n  ack_channels: []\n", {"--mode", "fast"}), "");
}

}  // namespace
}  // namespace bmp::capture

#include "detector/detector_settings.hpp"

#include <gtest/gtest.h>

#include <functional>
#include <stdexcept>
#include <string>

#include "detector_test_util.hpp"

namespace bmp::detector {
namespace {

std::string configErrorOf(const std::function<void()>& fn) {
  try {
    fn();
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "(no ConfigError)";
}

TEST(DetectorSettings, RepositoryFileGivesTheDocumentedDefaults) {
  const std::string dir = test::sourceDir() + "/config";
  const auto config = Config::fromFile(dir + "/detector.yaml");
  const DetectorSettings s = detectorSettingsFromConfig(config, std::nullopt, "/unused");
  EXPECT_EQ(s.mode, QueueMode::kLatest);
  EXPECT_EQ(s.queue_capacity, 64u);
  EXPECT_EQ(s.latest_nice, 10);
  EXPECT_EQ(s.latest_nice, DetectorSettings{}.latest_nice);
  EXPECT_EQ(s.frames_channel, "RGBD_FRAME");
  EXPECT_EQ(s.detections_channel, "DETECTIONS");
  EXPECT_EQ(s.detector.input_size, 320);
  EXPECT_EQ(s.dynamic_classes_path, dir + "/dynamic_classes.yaml");  // beside the file that names it
  EXPECT_NO_THROW(config.finish());                                  // every key was read
}

TEST(DetectorSettings, ReadsProcessAndChannelsAndTheModeOverride) {
  const auto config = Config::fromString(
      "dynamic_classes: levels.yaml\n"
      "process: {mode: every, queue_capacity: 3, latest_nice: 0}\n"
      "channels: {frames: F, detections: D}\n",
      "(test)");
  DetectorSettings s = detectorSettingsFromConfig(config, std::nullopt, "/configs");
  EXPECT_EQ(s.mode, QueueMode::kEvery);
  EXPECT_EQ(s.queue_capacity, 3u);
  EXPECT_EQ(s.latest_nice, 0);
  EXPECT_EQ(s.frames_channel, "F");
  EXPECT_EQ(s.detections_channel, "D");
  EXPECT_EQ(s.dynamic_classes_path, "/configs/levels.yaml");  // not a file: the fallback folder
  s = detectorSettingsFromConfig(config, std::string("latest"), "/configs");
  EXPECT_EQ(s.mode, QueueMode::kLatest);
}

TEST(DetectorSettings, BadModeIsAConfigErrorNamingFileAndKey) {
  const auto config = Config::fromString("process: {mode: newest}", "m.yaml");
  const std::string msg = configErrorOf([&] { detectorSettingsFromConfig(config, std::nullopt, "/"); });
  EXPECT_EQ(msg, "m.yaml: key 'process.mode' or --mode: mode must be 'latest' or 'every', got 'newest'");

  const auto fine = Config::fromString("process: {mode: every}", "o.yaml");
  const std::string from_option =
      configErrorOf([&] { detectorSettingsFromConfig(fine, std::string("all"), "/"); });
  EXPECT_EQ(from_option, "o.yaml: key 'process.mode' or --mode: mode must be 'latest' or 'every', got 'all'");
}

TEST(DetectorSettings, BadQueueCapacityIsAConfigErrorNamingFileAndKey) {
  for (const char* yaml : {"process: {queue_capacity: 0}", "process: {queue_capacity: -4}"}) {
    const auto config = Config::fromString(yaml, "q.yaml");
    const std::string msg = configErrorOf([&] { detectorSettingsFromConfig(config, std::nullopt, "/"); });
    EXPECT_EQ(msg, "q.yaml: key 'process.queue_capacity' must be >= 1") << yaml;
  }
  const auto wrong_type = Config::fromString("process: {queue_capacity: many}", "t.yaml");
  const std::string msg = configErrorOf([&] { detectorSettingsFromConfig(wrong_type, std::nullopt, "/"); });
  EXPECT_NE(msg.find("t.yaml"), std::string::npos) << msg;
  EXPECT_NE(msg.find("process.queue_capacity"), std::string::npos) << msg;
}

TEST(DetectorSettings, NiceOutsideZeroToNineteenIsAConfigError) {
  for (const char* yaml : {"process: {latest_nice: -1}", "process: {latest_nice: 20}"}) {
    const auto config = Config::fromString(yaml, "n.yaml");
    const std::string msg = configErrorOf([&] { detectorSettingsFromConfig(config, std::nullopt, "/"); });
    EXPECT_EQ(msg, "n.yaml: key 'process.latest_nice' must be in [0, 19]") << yaml;
  }
}

TEST(DetectorSettings, ParsesQueueModes) {
  EXPECT_EQ(parseQueueMode("latest"), QueueMode::kLatest);
  EXPECT_EQ(parseQueueMode("every"), QueueMode::kEvery);
  EXPECT_THROW(parseQueueMode("newest"), std::invalid_argument);
  EXPECT_STREQ(toString(QueueMode::kEvery), "every");
}

}  // namespace
}  // namespace bmp::detector

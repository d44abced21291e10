#include <gtest/gtest.h>

#include <fstream>
#include <random>

#include "bmp/common/image_codec.hpp"
#include "detector/detection_worker.hpp"
#include "detector_test_util.hpp"

namespace bmp::detector {
namespace {

using test::cocoNames;

std::string messageOf(const std::function<void()>& fn) {
  try {
    fn();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "(no exception)";
}

TEST(DetectorLevels, RepositoryTableMapsEveryCocoClass) {
  const auto names = cocoNames();
  ASSERT_EQ(names.size(), 80u);
  const auto table = DynamicClassTable::fromConfig(test::repoDynamicClasses(), names);
  EXPECT_EQ(table.size(), 80u);
  for (const char* name : {"person", "dog", "cat", "horse", "bird"})
    EXPECT_EQ(table.levelOf(name), DynamicLevel::kHigh) << name;
  for (const char* name : {"chair", "cup", "book", "cell phone", "remote", "backpack", "handbag", "bottle"})
    EXPECT_EQ(table.levelOf(name), DynamicLevel::kMedium) << name;
  for (const char* name : {"tvmonitor", "refrigerator", "diningtable", "sofa", "bed", "sink"})
    EXPECT_EQ(table.levelOf(name), DynamicLevel::kLow) << name;
  EXPECT_THROW(table.levelOf("unicorn"), std::out_of_range);
}

TEST(DetectorLevels, UnknownClassNameIsAConfigErrorNamingFileAndKey) {
  const std::vector<std::string> names = {"person", "chair", "tvmonitor"};
  const auto config = Config::fromString("high: [person]\nmedium: [chair]\nlow: [tv monitor]\n", "dyn.yaml");
  const std::string msg = messageOf([&] { DynamicClassTable::fromConfig(config, names); });
  EXPECT_NE(msg.find("dyn.yaml"), std::string::npos) << msg;
  EXPECT_NE(msg.find("'low'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("'tv monitor'"), std::string::npos) << msg;
  EXPECT_THROW(DynamicClassTable::fromConfig(config, names), ConfigError);
}

TEST(DetectorLevels, UnmappedDuplicateAndStrayKeysAreErrors) {
  const std::vector<std::string> names = {"person", "chair", "tvmonitor"};
  const auto unmapped = Config::fromString("high: [person]\nmedium: [chair]\nlow: []\n", "a.yaml");
  EXPECT_NE(messageOf([&] { DynamicClassTable::fromConfig(unmapped, names); }).find("'tvmonitor'"),
            std::string::npos);
  const auto twice =
      Config::fromString("high: [person, chair]\nmedium: [chair]\nlow: [tvmonitor]\n", "b.yaml");
  EXPECT_THROW(DynamicClassTable::fromConfig(twice, names), ConfigError);
  const auto stray =
      Config::fromString("high: [person]\nmedium: [chair]\nlow: [tvmonitor]\nhihg: []\n", "c.yaml");
  EXPECT_NE(messageOf([&] { DynamicClassTable::fromConfig(stray, names); }).find("hihg"), std::string::npos);
  const auto missing = Config::fromString("high: [person]\nlow: [tvmonitor, chair]\n", "d.yaml");
  EXPECT_THROW(DynamicClassTable::fromConfig(missing, names), ConfigError);
}

TEST(DetectorConfigYaml, ReadsRepositoryFileAndRejectsBadValues) {
  const auto file = Config::fromFile(test::sourceDir() + "/config/detector.yaml");
  const DetectorConfig c = detectorConfigFromYaml(file);
  EXPECT_EQ(c.kind, ModelKind::kOnnx);
  EXPECT_EQ(c.input_size, 320);
  EXPECT_EQ(c.threads, 2);
  EXPECT_EQ(c.model_path, "models/yolov5n/yolov5n_coco_320.onnx");

  EXPECT_THROW(detectorConfigFromYaml(Config::fromString("model: {kind: tflite}", "k.yaml")), ConfigError);
  EXPECT_THROW(detectorConfigFromYaml(Config::fromString("model: {input_size: 100}", "s.yaml")), ConfigError);
  const std::string msg = messageOf(
      [] { detectorConfigFromYaml(Config::fromString("detection: {conf_threshold: 1.5}", "t.yaml")); });
  EXPECT_NE(msg.find("detection.conf_threshold"), std::string::npos) << msg;
  // More boxes than a DETECTIONS answer may carry: the tracker would refuse every busy frame's answer.
  EXPECT_EQ(
      detectorConfigFromYaml(Config::fromString("detection: {max_detections: 300}", "m.yaml")).max_detections,
      300);
  const std::string many = messageOf(
      [] { detectorConfigFromYaml(Config::fromString("detection: {max_detections: 301}", "m.yaml")); });
  EXPECT_NE(many.find("'detection.max_detections' must be in [1, 300]"), std::string::npos) << many;
}

TEST(DetectorModel, MissingModelFileFailsAtStartUpNamingIt) {
  DetectorConfig c = test::presetConfig("yolov5n-320");
  c.model_path = "/nonexistent/yolov5n.onnx";
  const std::string msg = messageOf([&] { Detector d(c, test::repoDynamicClasses()); });
  EXPECT_NE(msg.find("/nonexistent/yolov5n.onnx"), std::string::npos) << msg;
  EXPECT_NE(msg.find("not found"), std::string::npos) << msg;
  EXPECT_THROW(Detector(c, test::repoDynamicClasses()), ModelError);
}

TEST(DetectorModel, CorruptModelFileFailsAtStartUpNamingIt) {
  const auto dir = test::scratchDir("detector_corrupt_model");
  const std::string onnx = (dir / "garbage.onnx").string();
  const std::string weights = (dir / "garbage.weights").string();
  std::mt19937 rng(7);
  for (const auto& path : {onnx, weights}) {
    std::ofstream out(path, std::ios::binary);
    for (int i = 0; i < 4096; ++i) out.put(static_cast<char>(rng() & 0xff));
  }
  DetectorConfig c = test::presetConfig("yolov5n-320");
  c.model_path = onnx;
  const std::string msg = messageOf([&] { Detector d(c, test::repoDynamicClasses()); });
  EXPECT_NE(msg.find(onnx), std::string::npos) << msg;
  EXPECT_THROW(Detector(c, test::repoDynamicClasses()), ModelError);

  DetectorConfig d = test::presetConfig("yolo-fastest-xl");
  d.model_path = weights;
  EXPECT_THROW(Detector(d, test::repoDynamicClasses()), ModelError);
}

TEST(DetectorModel, InputSizeNotMatchingTheModelFailsAtStartUp) {
  DetectorConfig c = test::presetConfig("yolov5n-320");
  c.input_size = 640;  // the 320 model has a fixed input shape
  const std::string msg = messageOf([&] { Detector d(c, test::repoDynamicClasses()); });
  EXPECT_NE(msg.find("yolov5n_coco_320.onnx"), std::string::npos) << msg;
  EXPECT_THROW(Detector(c, test::repoDynamicClasses()), ModelError);
}

TEST(DetectorModel, UnknownClassInDynamicLevelsFailsAtStartUp) {
  auto bad = Config::fromString("high: [person, persn]\nmedium: []\nlow: []\n", "bad_dynamic.yaml");
  const std::string msg = messageOf([&] { Detector d(test::presetConfig("yolov5n-320"), bad); });
  EXPECT_NE(msg.find("bad_dynamic.yaml"), std::string::npos) << msg;
  EXPECT_NE(msg.find("'persn'"), std::string::npos) << msg;
}

// Stopped with frames waiting: each frame is either answered (the one in progress) or still waiting, never
// neither. The count at exit once fell between the two and missed a frame.
TEST(DetectorWorker, AfterFinishEveryFrameIsAnsweredOrWaiting) {
  Detector detector(test::presetConfig("yolov5n-320"), test::repoDynamicClasses());
  FrameJob frame;
  frame.color.data = readFileBytes(test::bonnDir() + "/rgb/1548339829.89644.jpg");
  frame.color.width = 640;
  frame.color.height = 480;
  frame.color.encoding = ImageEncoding::kJpeg;
  for (int wait_ms : {0, 5, 60}) {
    DetectionWorker worker(detector, QueueMode::kEvery, 8);
    for (int i = 0; i < 5; ++i) {
      frame.seq = i;
      worker.submit(frame);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(wait_ms));
    worker.finish();
    const std::size_t answered = worker.takeResults().size();
    EXPECT_EQ(answered + worker.unfinished(), 5u) << "after " << wait_ms << " ms";
  }
}

TEST(DetectorWorker, UndecodableColourBytesAreSkippedWithAReasonAndTheNextFrameIsAnswered) {
  Detector detector(test::presetConfig("yolov5n-320"), test::repoDynamicClasses());
  FrameJob bad;
  bad.seq = 4;
  bad.utime = 1000;
  bad.color.width = 640;
  bad.color.height = 480;
  bad.color.encoding = ImageEncoding::kJpeg;
  bad.color.data = {0xde, 0xad, 0xbe, 0xef, 0x00, 0x01, 0x02};
  const FrameResult direct = processFrame(detector, bad);
  EXPECT_FALSE(direct.ok);
  EXPECT_NE(direct.error.find("undecodable"), std::string::npos) << direct.error;

  FrameJob good;
  good.seq = 5;
  good.utime = 2000;
  good.color.data = readFileBytes(test::bonnDir() + "/rgb/1548339829.89644.jpg");
  good.color.width = 640;
  good.color.height = 480;
  good.color.encoding = ImageEncoding::kJpeg;

  std::vector<FrameResult> results;
  {
    DetectionWorker worker(detector, QueueMode::kEvery, 4);
    worker.submit(bad);
    worker.submit(good);
    for (int i = 0; i < 1500 && results.size() < 2; ++i) {  // 30 s: two inferences on a loaded machine
      for (auto& r : worker.takeResults()) results.push_back(std::move(r));
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  }
  ASSERT_EQ(results.size(), 2u);
  EXPECT_EQ(results[0].seq, 4);
  EXPECT_FALSE(results[0].ok);
  EXPECT_EQ(results[1].seq, 5);
  EXPECT_EQ(results[1].utime, 2000);
  ASSERT_TRUE(results[1].ok) << results[1].error;
  EXPECT_GE(results[1].detections.size(), 2u);
  EXPECT_GT(results[1].total_ms, 0.0);
}

}  // namespace
}  // namespace bmp::detector

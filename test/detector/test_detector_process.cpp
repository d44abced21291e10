// The real bmp-detector over LCM: frames in, one DETECTIONS message per processed frame out.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <sstream>
#include <thread>

#include <bmp/detections_t.hpp>
#include <bmp/process_status_t.hpp>
#include <bmp/rgbd_frame_t.hpp>

#include "bmp/common/camera_config.hpp"
#include "bmp/common/child_process.hpp"
#include "bmp/common/image_codec.hpp"
#include "bmp/common/stamp.hpp"
#include "bmp/lcm/conversions.hpp"
#include "bmp/lcm/lcm_node.hpp"
#include "file_image.hpp"
#include "lcm_url.hpp"
#include "shared_data.hpp"

namespace bmp {
namespace {

struct BonnFrame {
  double stamp = 0.0;
  std::string color_path;
  std::string depth_path;
};

// n colour frames of the Bonn sequence from index first, each with the depth image of the same index (close
// enough in time for this test; association is the capture process's job).
std::vector<BonnFrame> bonnFrames(std::size_t first, std::size_t n) {
  const auto read = [](const std::string& list) {
    std::ifstream in(test::bonnDir() + "/" + list);
    std::vector<std::pair<double, std::string>> out;
    for (std::string line; std::getline(in, line);) {
      if (line.empty() || line[0] == '#') continue;
      std::istringstream f(line);
      double stamp;
      std::string file;
      // depth.txt names a few files that do not exist (a known defect of the source).
      if (f >> stamp >> file && std::ifstream(test::bonnDir() + "/" + file))
        out.emplace_back(stamp, test::bonnDir() + "/" + file);
    }
    return out;
  };
  const auto rgb = read("rgb.txt");
  const auto depth = read("depth.txt");
  std::vector<BonnFrame> frames;
  for (std::size_t i = first; i < first + n && i < rgb.size() && i < depth.size(); ++i)
    frames.push_back({rgb[i].first, rgb[i].second, depth[i].second});
  return frames;
}

rgbd_frame_t frameMessage(int64_t seq, const BonnFrame& frame) {
  rgbd_frame_t msg;
  msg.seq = seq;
  msg.utime = secondsToUtime(frame.stamp);
  msg.depth_utime = msg.utime;
  msg.source = "rgbd_bonn_crowd";
  // The frame contract asks for the camera; the detector refuses frames without usable intrinsics.
  static const CameraIntrinsics camera =
      cameraFromConfig(Config::fromFile(BMP_SOURCE_DIR "/config/cameras/bonn.yaml").section("camera"));
  msg.camera = toMsg(camera);
  msg.depth_scale = camera.depth_scale;
  msg.color = test::fileImage(frame.color_path, PixelFormat::kBgr8);
  msg.depth = test::fileImage(frame.depth_path, PixelFormat::kMono16);
  return msg;
}

// One bmp-detector child on a test-unique LCM port, and what it publishes.
class DetectorProcess : public ::testing::Test {
 protected:
  void start(const std::string& mode, int slot, const std::vector<std::string>& extra = {}) {
    const std::string url = test::uniqueLcmUrl(slot);
    log_path_ = (test::scratchDir("detector_process_" + mode) / "bmp-detector.log").string();
    node_ = std::make_unique<LcmNode>(url);
    node_->subscribe<detections_t>("DETECTIONS", [this](const detections_t& msg, const ReceivedInfo&) {
      if (!resends_) {
        EXPECT_EQ(answers_.count(msg.seq), 0u) << "two answers for seq " << msg.seq;
      }
      answers_[msg.seq] = msg;
      order_.push_back(msg.seq);
    });
    node_->subscribe<process_status_t>("PROCESS_STATUS",
                                       [this](const process_status_t& msg, const ReceivedInfo&) {
                                         if (msg.name == "bmp-detector") statuses_.push_back(msg);
                                       });
    std::vector<std::string> command = {test::binPath("bmp-detector"),
                                        "--config",
                                        test::sourceDir() + "/config/detector.yaml",
                                        "--lcm-url",
                                        url,
                                        "--mode",
                                        mode};
    command.insert(command.end(), extra.begin(), extra.end());
    child_ = std::make_unique<ChildProcess>(command, ChildProcess::Output::kFile, log_path_);
    // The first heartbeat comes once the model is loaded and the subscription is in place.
    ASSERT_TRUE(pumpUntil([&] { return !statuses_.empty() || !child_->running(); }, 60.0))
        << "no heartbeat; log in " << log_path_;
    ASSERT_TRUE(child_->running()) << "bmp-detector exited; log in " << log_path_;
  }

  bool pumpUntil(const std::function<bool()>& done, double timeout_s) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
    while (!done() && std::chrono::steady_clock::now() < end) node_->handle(50);
    return done();
  }

  // SIGINT; returns the final heartbeat (state FINISHED).
  process_status_t stop() {
    EXPECT_EQ(child_->stop(15.0), 0) << diagnosis();
    pumpUntil(
        [&] { return !statuses_.empty() && statuses_.back().state == process_status_t::STATE_FINISHED; },
        2.0);
    EXPECT_FALSE(statuses_.empty());
    return statuses_.empty() ? process_status_t{} : statuses_.back();
  }

  std::string log() const { return test::readText(log_path_); }

  // What a failure needs to tell a lost frame (the heartbeat's lost) from a slow or stuck detector: the seqs
  // answered, the last heartbeat's counts and the process's log.
  std::string diagnosis() const {
    std::ostringstream out;
    out << answers_.size() << " answer(s), seqs";
    for (const auto& [seq, msg] : answers_) out << " " << seq;
    if (statuses_.empty()) {
      out << "; no heartbeat";
    } else {
      const process_status_t& s = statuses_.back();
      out << "; last heartbeat: received " << s.received << ", processed " << s.processed << ", dropped "
          << s.dropped << ", lost " << s.lost << ", malformed " << s.malformed << ", message '" << s.message
          << "'";
    }
    out << "; log " << log_path_ << ":\n" << log();
    return out.str();
  }

  std::unique_ptr<LcmNode> node_;
  std::unique_ptr<ChildProcess> child_;
  std::string log_path_;
  std::map<int64_t, detections_t> answers_;
  std::vector<int64_t> order_;
  std::vector<process_status_t> statuses_;
  bool resends_ = false;  // the test sends frames again, as lockstep capture does: their answers come again
};

TEST_F(DetectorProcess, EveryModeAnswersEachFrameAndSkipsAnUndecodableOne) {
  ASSERT_NO_FATAL_FAILURE(start("every", 0));
  constexpr int kBadSeq = 4;
  const auto frames = bonnFrames(445, 10);  // three people walk through these
  ASSERT_EQ(frames.size(), 10u);
  std::map<int64_t, int64_t> sent_utime;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    rgbd_frame_t msg = frameMessage(static_cast<int64_t>(i), frames[i]);
    if (msg.seq == kBadSeq) {
      // The encoding's signature with garbage behind it: passes the frame checks, fails the decoder.
      const std::vector<uint8_t> signature =
          msg.color.encoding == image_t::ENCODING_JPEG
              ? std::vector<uint8_t>{0xFF, 0xD8, 0xFF}
              : std::vector<uint8_t>{0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
      msg.color.data.assign(5000, 0x5a);
      std::copy(signature.begin(), signature.end(), msg.color.data.begin());
      msg.color.size = static_cast<int32_t>(msg.color.data.size());
    }
    sent_utime[msg.seq] = msg.utime;
    node_->publish("RGBD_FRAME", msg);
    node_->handle(30);
  }
  ASSERT_TRUE(pumpUntil([&] { return answers_.size() >= frames.size(); }, 60.0)) << diagnosis();
  pumpUntil([] { return false; }, 0.5);  // nothing more may come

  // Every frame is answered, the undecodable one too: with its reason and no boxes.
  EXPECT_EQ(answers_.size(), frames.size());
  ASSERT_EQ(answers_.count(kBadSeq), 1u);
  const detections_t bad = answers_.at(kBadSeq);
  EXPECT_NE(bad.skipped.find("colour image"), std::string::npos) << bad.skipped;
  EXPECT_EQ(bad.num_detections, 0);
  EXPECT_EQ(bad.utime, sent_utime.at(kBadSeq));
  answers_.erase(kBadSeq);
  int persons = 0;
  for (const auto& [seq, msg] : answers_) {
    EXPECT_EQ(msg.utime, sent_utime.at(seq)) << "seq " << seq;
    EXPECT_EQ(msg.model, "yolov5n_coco_320");
    EXPECT_TRUE(msg.skipped.empty()) << "seq " << seq << ": " << msg.skipped;
    EXPECT_EQ(msg.image_width, 640);
    EXPECT_EQ(msg.image_height, 480);
    EXPECT_EQ(msg.num_detections, static_cast<int32_t>(msg.detections.size()));
    EXPECT_GT(msg.inference_ms, 0.0f);
    for (const auto& d : msg.detections) {
      EXPECT_GE(d.class_id, 0);
      EXPECT_LT(d.class_id, 80);
      if (d.label == "person") {
        EXPECT_EQ(static_cast<int>(d.dynamic_level), static_cast<int>(detection_t::LEVEL_HIGH));
        ++persons;
      }
    }
  }
  EXPECT_GE(persons, 2 * static_cast<int>(answers_.size()));

  const process_status_t last = stop();
  EXPECT_EQ(static_cast<int>(last.state), static_cast<int>(process_status_t::STATE_FINISHED)) << diagnosis();
  EXPECT_EQ(last.received, 10) << diagnosis();
  EXPECT_EQ(last.processed, 9);
  EXPECT_EQ(last.malformed, 1);
  EXPECT_EQ(last.dropped, 0);
  EXPECT_NE(last.message.find("seq " + std::to_string(kBadSeq)), std::string::npos) << last.message;
  // Before the camera settles (5 frames) the stream's walk over the JPEG names the damage; after, decoding.
  EXPECT_NE(log().find("frame seq " + std::to_string(kBadSeq) + ": colour image: "), std::string::npos)
      << log();
}

// The nice value of each of a process's threads (/proc/PID/task/TID/stat, field 19).
std::vector<int> threadNiceValues(pid_t pid) {
  std::vector<int> nice;
  for (const auto& task : std::filesystem::directory_iterator("/proc/" + std::to_string(pid) + "/task")) {
    std::ifstream in(task.path() / "stat");
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::istringstream fields(text.substr(text.rfind(')') + 2));  // after "pid (comm) "
    std::string field;
    for (int i = 3; i <= 19 && fields >> field; ++i)
      if (i == 19) nice.push_back(std::stoi(field));
  }
  return nice;
}

int ownNice() {
  return threadNiceValues(::getpid()).front();
}

// Real time: the detector yields the CPU to the tracker (process.latest_nice, 10): the main thread and the
// threads it starts afterwards (the inference worker) run at nice 10. Lockstep ('every') is left alone.
TEST_F(DetectorProcess, LatestModeRunsNicer) {
  ASSERT_NO_FATAL_FAILURE(start("latest", 3));
  const std::vector<int> nice = threadNiceValues(child_->pid());
  const int wanted = std::max(10, ownNice());  // a test run started nicer stays so
  EXPECT_GE(std::count(nice.begin(), nice.end(), wanted), 2) << "main thread and worker";
  stop();
}

TEST_F(DetectorProcess, EveryModeKeepsItsPriority) {
  ASSERT_NO_FATAL_FAILURE(start("every", 4));
  const std::vector<int> nice = threadNiceValues(child_->pid());
  ASSERT_FALSE(nice.empty());
  EXPECT_EQ(std::count(nice.begin(), nice.end(), ownNice()), static_cast<long>(nice.size()));
  stop();
}

TEST_F(DetectorProcess, LatestModeWorksOnTheNewestFrameAndCountsDrops) {
  ASSERT_NO_FATAL_FAILURE(start("latest", 1));
  const auto frames = bonnFrames(445, 20);
  ASSERT_EQ(frames.size(), 20u);
  std::vector<rgbd_frame_t> messages;
  for (std::size_t i = 0; i < frames.size(); ++i)
    messages.push_back(frameMessage(static_cast<int64_t>(i), frames[i]));
  // Far faster than inference: most frames find the detector busy.
  for (const auto& msg : messages) node_->publish("RGBD_FRAME", msg);
  ASSERT_TRUE(pumpUntil([&] { return answers_.count(19) == 1; }, 30.0))
      << "the newest frame was not answered; " << diagnosis();
  pumpUntil([] { return false; }, 0.5);

  EXPECT_LT(answers_.size(), frames.size());
  EXPECT_TRUE(std::is_sorted(order_.begin(), order_.end()));
  const process_status_t last = stop();
  EXPECT_EQ(last.received, 20);
  EXPECT_GT(last.dropped, 0);
  EXPECT_EQ(last.processed, static_cast<int64_t>(answers_.size()));
  EXPECT_EQ(last.processed + last.dropped, last.received);
  EXPECT_EQ(last.malformed, 0);
}

// Another publisher's frame, refused, comes between a frame and lockstep capture sending that frame again:
// the resend is still answered with the frame's boxes. The refusal's answer took the place of the frame's,
// and capture waited for an answer that never came.
TEST_F(DetectorProcess, ARefusedFrameDoesNotReplaceTheAnswerAResendRepeats) {
  resends_ = true;
  ASSERT_NO_FATAL_FAILURE(start("every", 5));
  const auto frames = bonnFrames(445, 2);
  ASSERT_EQ(frames.size(), 2u);
  const auto answered = [&](int64_t seq) { return std::count(order_.begin(), order_.end(), seq); };
  const rgbd_frame_t real = frameMessage(0, frames[0]);
  node_->publish("RGBD_FRAME", real);
  ASSERT_TRUE(pumpUntil([&] { return answered(0) == 1; }, 60.0)) << diagnosis();
  const detections_t first = answers_.at(0);
  ASSERT_GT(first.num_detections, 0) << "people walk through these frames";
  rgbd_frame_t forged = frameMessage(1, frames[1]);
  forged.depth_scale = 0.0;
  node_->publish("RGBD_FRAME", forged);
  ASSERT_TRUE(pumpUntil([&] { return answered(1) == 1; }, 30.0)) << diagnosis();
  EXPECT_FALSE(answers_.at(1).skipped.empty());
  node_->publish("RGBD_FRAME", real);
  ASSERT_TRUE(pumpUntil([&] { return answered(0) == 2; }, 30.0))
      << "the resend was not answered; " << diagnosis();
  EXPECT_EQ(answers_.at(0).utime, real.utime);
  EXPECT_EQ(answers_.at(0).num_detections, first.num_detections);
  EXPECT_TRUE(answers_.at(0).skipped.empty());
  const process_status_t last = stop();
  EXPECT_EQ(last.processed, 1) << "the resend is answered again, not detected again";
}

// Another publisher's damaged copy of a frame (the same seq and stamp, depth_scale 0) is refused and not
// answered: the refusal went out first, under the real frame's name, and the tracker kept it in place of the
// frame's boxes. The frame's own answer is its only one.
TEST_F(DetectorProcess, ADamagedCopyOfAFrameIsNotAnsweredInItsName) {
  ASSERT_NO_FATAL_FAILURE(start("every", 6));  // the fixture fails a second answer for a seq
  const auto frames = bonnFrames(445, 2);
  ASSERT_EQ(frames.size(), 2u);
  const rgbd_frame_t real = frameMessage(0, frames[0]);
  rgbd_frame_t copy = real;
  copy.depth_scale = 0.0;
  node_->publish("RGBD_FRAME", real);
  node_->publish("RGBD_FRAME", copy);
  node_->publish("RGBD_FRAME", frameMessage(1, frames[1]));
  ASSERT_TRUE(pumpUntil([&] { return answers_.count(1) == 1; }, 60.0)) << diagnosis();
  ASSERT_EQ(std::count(order_.begin(), order_.end(), 0), 1) << diagnosis();
  EXPECT_TRUE(answers_.at(0).skipped.empty()) << answers_.at(0).skipped;
  EXPECT_GT(answers_.at(0).num_detections, 0) << "people walk through these frames";
  const process_status_t last = stop();
  EXPECT_EQ(last.processed, 2);
  EXPECT_EQ(last.malformed, 1);
  EXPECT_NE(log().find("depth_scale must be positive (a damaged copy of a frame taken; not answered)"),
            std::string::npos)
      << log();
}

// --model swaps the configuration's model for one from the shared folder (a lockstep run that compares with
// the paper, whose detector sees 640 px): the process says so, and answers with it.
TEST_F(DetectorProcess, AModelNamedOnTheCommandLineReplacesTheConfiguredOne) {
  ASSERT_NO_FATAL_FAILURE(start("every", 2, {"--model", "yolov5n-640"}));
  const auto frames = bonnFrames(445, 1);
  ASSERT_EQ(frames.size(), 1u);
  node_->publish("RGBD_FRAME", frameMessage(0, frames[0]));
  ASSERT_TRUE(pumpUntil([&] { return answers_.count(0) == 1; }, 60.0)) << diagnosis();
  EXPECT_NE(answers_.at(0).model.find("640"), std::string::npos) << answers_.at(0).model;
  stop();
  EXPECT_NE(log().find("yolov5n_coco_640.onnx"), std::string::npos) << log();
}

// A name it does not know stops it at start-up, naming the option and the names it knows.
TEST(DetectorProcessStartUp, AnUnknownModelNameIsAnErrorNamingTheOption) {
  const auto dir = test::scratchDir("detector_process_unknown_model");
  const std::string log_path = (dir / "bmp-detector.log").string();
  ChildProcess child({test::binPath("bmp-detector"), "--config", test::sourceDir() + "/config/detector.yaml",
                      "--lcm-url", test::uniqueLcmUrl(14), "--model", "yolov9"},
                     ChildProcess::Output::kFile, log_path);
  EXPECT_EQ(child.wait(30.0), 2);
  const std::string log = test::readText(log_path);
  EXPECT_NE(log.find("--model: unknown model 'yolov9'"), std::string::npos) << log;
  EXPECT_NE(log.find("yolov5n-640"), std::string::npos) << log;
}

TEST(DetectorProcessStartUp, MissingModelIsAConfigurationErrorBeforeAnyFrame) {
  const auto dir = test::scratchDir("detector_process_missing_model");
  const std::string config = (dir / "detector.yaml").string();
  std::ofstream(config) << "model:\n  path: " << (dir / "absent.onnx").string()
                        << "\ndynamic_classes: " << test::sourceDir() << "/config/dynamic_classes.yaml\n";
  const std::string log_path = (dir / "bmp-detector.log").string();
  ChildProcess child({test::binPath("bmp-detector"), "--config", config, "--lcm-url", test::uniqueLcmUrl(15)},
                     ChildProcess::Output::kFile, log_path);
  EXPECT_EQ(child.wait(30.0), 2);
  const std::string log = test::readText(log_path);
  EXPECT_NE(log.find((dir / "absent.onnx").string() + ": ONNX model file not found"), std::string::npos)
      << log;
}

}  // namespace
}  // namespace bmp

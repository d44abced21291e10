// A hostile publisher on the bus of a running pipeline (bmp-run, Bonn, lockstep, over real udpm): every
// message the issue tried by hand, and random, truncated and oversized bytes on every channel. No process
// may exit or stall, every bad message must be counted where it arrived, and the trajectory must stay good.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <limits>
#include <mutex>
#include <optional>
#include <thread>

#include <bmp/detections_t.hpp>
#include <bmp/keyframe_poses_t.hpp>
#include <bmp/keyframe_t.hpp>
#include <bmp/process_status_t.hpp>
#include <bmp/rgbd_frame_t.hpp>
#include <bmp/slam_pose_t.hpp>

#include "bmp/common/child_process.hpp"
#include "bmp/lcm/lcm_node.hpp"
#include "hostile_support.hpp"
#include "integration_support.hpp"

namespace bmp {
namespace {

namespace fs = std::filesystem;
using test::binPath;

// What the hostile publisher sent on each channel, for the counts each subscriber must show.
struct Sent {
  int frames = 0;      // RGBD_FRAME: every one must be malformed or refused at the tracker and the detector
  int detections = 0;  // DETECTIONS: each one neither decodes nor answers a frame capture sent
  int poses = 0;       // SLAM_POSE: likewise, for capture
  int keyframes = 0;   // SLAM_KEYFRAME and SLAM_KEYFRAME_POSES: malformed at the mapper
};

// A raw 16x12 frame of another camera that is perfectly valid on its own.
rgbd_frame_t otherCameraFrame(const rgbd_frame_t& real) {
  rgbd_frame_t f = real;
  f.camera.width = 16;
  f.camera.height = 12;
  f.camera.cx = 8;
  f.camera.cy = 6;
  for (image_t* img : {&f.color, &f.depth}) {
    img->width = 16;
    img->height = 12;
    img->encoding = image_t::ENCODING_RAW;
  }
  f.color.size = 16 * 12 * 3;
  f.color.data.assign(static_cast<std::size_t>(f.color.size), 100);
  f.depth.size = 16 * 12 * 2;
  f.depth.data.assign(static_cast<std::size_t>(f.depth.size), 20);
  return f;
}

// Frames built from a real one (heard on the bus) that decode but must be refused: each with a reason.
int publishBadFrames(LcmNode& lcm, const rgbd_frame_t& real) {
  // First, while the real next frame is most likely still waiting for its answers: the next seq with a stamp
  // from before, refused as out of order (or, if the real one came first, as a seq that does not follow).
  rgbd_frame_t back = real;
  back.seq = real.seq + 1;
  back.utime = real.utime - 1000000;
  std::vector<rgbd_frame_t> bad(5, real);
  bad[0] = back;
  // The others carry the real frame's own seq: they can never look like a gap (lost) at any consumer.
  bad[1].camera.fx = std::nan("");
  bad[2].camera.fx = 0;
  bad[3].depth_scale = 0;
  bad[4] = otherCameraFrame(real);
  for (const auto& f : bad) {
    lcm.publish("RGBD_FRAME", f);
    test::pace();
  }
  // Declared lengths the bytes cannot back: colour size -1 and 2^31-1.
  for (int32_t size : {-1, std::numeric_limits<int32_t>::max()}) {
    rgbd_frame_t small{};
    small.source = "x";
    auto buf = test::encoded(small);
    test::putInt32(buf, 8 + 3 * 8 + 4 + small.source.size() + 1 + 80 + 8 + 10, size);
    lcm.raw().publish("RGBD_FRAME", buf.data(), static_cast<unsigned>(buf.size()));
    test::pace();
  }
  return static_cast<int>(bad.size()) + 2 + test::publishJunk(lcm, "RGBD_FRAME", real, 1);
}

Sent publishHostile(LcmNode& lcm, const rgbd_frame_t& real) {
  Sent sent;
  sent.frames = publishBadFrames(lcm, real);
  detections_t forged{};
  forged.model = "forged";
  forged.seq = std::numeric_limits<int64_t>::max();
  forged.utime = real.utime;
  lcm.publish("DETECTIONS", forged);
  // The real next frame's seq with a wrong stamp: a well-formed answer for no frame, kept apart from the real
  // one (lockstep still gets the real boxes, so "no answer on" stays out of capture's log).
  detections_t next_seq = forged;
  next_seq.seq = real.seq + 1;
  next_seq.utime = real.utime + 1;
  lcm.publish("DETECTIONS", next_seq);
  auto negative = test::encoded(detections_t{});
  test::putInt32(negative, negative.size() - 4, -1);  // num_detections = -1
  lcm.raw().publish("DETECTIONS", negative.data(), static_cast<unsigned>(negative.size()));
  sent.detections = 2 + test::publishJunk(lcm, "DETECTIONS", forged, 2);
  slam_pose_t pose{};
  pose.seq = std::numeric_limits<int64_t>::max();
  pose.utime = real.utime;
  pose.state = slam_pose_t::STATE_OK;
  lcm.publish("SLAM_POSE", pose);
  sent.poses = 1 + test::publishJunk(lcm, "SLAM_POSE", pose, 3);
  sent.keyframes = test::publishJunk(lcm, "SLAM_KEYFRAME", keyframe_t{}, 4) +
                   test::publishJunk(lcm, "SLAM_KEYFRAME_POSES", keyframe_poses_t{}, 5);
  process_status_t status{};
  status.name = "bmp-forged";
  test::publishJunk(lcm, "PROCESS_STATUS", status, 6);
  return sent;
}

double ateRmse(const std::string& eval_json) {
  const std::size_t ate = eval_json.find("\"ate\"");
  const std::size_t rmse = eval_json.find("\"rmse\": ", ate);
  if (ate == std::string::npos || rmse == std::string::npos) return NAN;
  return std::stod(eval_json.substr(rmse + 8));
}

TEST(HostileInput, PipelineSurvivesAndCountsEveryBadMessage) {
  const fs::path out = test::scratchDir("hostile_input") / "run";
  const std::string url = test::uniqueLcmUrl(0);
  LcmNode lcm(url, [](const std::string&) {});  // the test's own node hears its junk too: quietly
  std::mutex mutex;
  std::optional<rgbd_frame_t> latest;
  int frames_heard = 0;
  lcm.subscribe<rgbd_frame_t>("RGBD_FRAME", [&](const rgbd_frame_t& m, const ReceivedInfo&) {
    if (m.source != "rgbd_bonn_crowd") return;  // our own forged ones
    const std::lock_guard<std::mutex> lock(mutex);
    latest = m;
    ++frames_heard;
  });
  const fs::path log = out.parent_path() / "bmp-run.log";
  ChildProcess run({binPath("bmp-run"), "--dataset", test::bonnDir(), "--frames", "150", "--out",
                    out.string(), "--lcm-url", url},
                   ChildProcess::Output::kFile, log.string());
  // Three rounds while frames flow: early (the map is young), middle, late.
  std::vector<Sent> rounds;
  for (int round = 0; round < 3 && run.running(); ++round) {
    const int due = 20 + 40 * round;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(90);
    while (frames_heard < due && run.running() && std::chrono::steady_clock::now() < deadline) lcm.handle(20);
    if (frames_heard < due) break;
    rounds.push_back(publishHostile(lcm, *latest));
  }
  ASSERT_EQ(rounds.size(), 3u) << "the run ended or stalled before the hostile messages\n"
                               << test::readText(log.string());
  const int status = run.wait(180).value_or(-1);
  const std::string output = test::readText(log.string());
  ASSERT_EQ(status, 0) << output;  // no process ended early or failed

  Sent total;
  for (const Sent& s : rounds) {
    total.frames += s.frames;
    total.detections += s.detections;
    total.poses += s.poses;
    total.keyframes += s.keyframes;
  }
  const std::string capture_log = test::readText((out / "logs" / "bmp-capture.log").string());
  EXPECT_EQ(capture_log.find("no answer on"), std::string::npos) << "lockstep stalled\n" << capture_log;
  EXPECT_NE(capture_log.find("published 150 frames"), std::string::npos) << capture_log;
  const std::string summary = test::readText((out / "summary.json").string());
  const auto figure = [&](const char* name, const char* key) {
    return test::processFigure(summary, name, key);
  };
  EXPECT_GE(figure("bmp-tracker", "malformed"), total.frames + total.detections - 3) << summary;
  EXPECT_GE(figure("bmp-detector", "malformed"), total.frames) << summary;
  EXPECT_GE(figure("bmp-capture", "malformed"), total.detections + total.poses) << summary;
  EXPECT_GE(figure("bmp-mapper", "malformed"), total.keyframes) << summary;
  // Nothing the forged frames carried was taken for a lost frame, and the real ones were all tracked.
  EXPECT_EQ(figure("bmp-tracker", "lost"), 0) << summary;
  EXPECT_EQ(figure("bmp-detector", "lost"), 0) << summary;
  EXPECT_EQ(figure("bmp-tracker", "processed"), 150) << summary;
  const std::string tracker_log = test::readText((out / "logs" / "bmp-tracker.log").string());
  for (const char* reason : {"camera intrinsics are not finite", "focal length fx/fy must be positive",
                             "depth_scale must be positive", "camera changed mid-run"})
    EXPECT_NE(tracker_log.find(reason), std::string::npos) << reason;
  EXPECT_TRUE(tracker_log.find("stamp is not after") != std::string::npos ||
              tracker_log.find("does not follow") != std::string::npos);
  // As good as without them: Bonn's first 150 frames track to about 1 cm.
  const double ate = ateRmse(test::readText((out / "eval.json").string()));
  EXPECT_LT(ate, 0.03) << output;
}

}  // namespace
}  // namespace bmp

namespace bmp {
namespace {

// A 50 MB message (another program's mistake) is ~800 datagrams at once: they overflow every receiver's
// socket buffer, and real frames or answers that arrive meanwhile are lost in the kernel. Lockstep capture
// publishes a frame again when its answers are late, and consumers answer the repeat, so the run goes on
// within a fraction of a second instead of waiting out the 5 s lockstep timeout, and every frame is
// tracked.
TEST(HostileInput, AFiftyMegabyteMessageCostsNoLockstepStall) {
  const fs::path out = test::scratchDir("hostile_50mb") / "run";
  const std::string url = test::uniqueLcmUrl(1);
  LcmNode lcm(url, [](const std::string&) {});
  int frames_heard = 0;
  lcm.subscribe<rgbd_frame_t>("RGBD_FRAME", [&](const rgbd_frame_t& m, const ReceivedInfo&) {
    if (m.source == "rgbd_bonn_crowd") ++frames_heard;
  });
  const fs::path log = out.parent_path() / "bmp-run.log";
  const int frames = 100;
  ChildProcess run({binPath("bmp-run"), "--dataset", test::bonnDir(), "--frames", std::to_string(frames),
                    "--out", out.string(), "--lcm-url", url},
                   ChildProcess::Output::kFile, log.string());
  const std::vector<uint8_t> huge = test::randomBytes(50u << 20, 9);
  int sent = 0;
  for (int due : {20, 50, 80}) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(90);
    while (frames_heard < due && run.running() && std::chrono::steady_clock::now() < deadline) lcm.handle(20);
    if (frames_heard < due) break;
    for (const char* channel : {"RGBD_FRAME", "SLAM_POSE"})
      lcm.raw().publish(channel, huge.data(), static_cast<unsigned>(huge.size()));
    ++sent;
  }
  ASSERT_EQ(sent, 3) << "the run ended or stalled first\n" << test::readText(log.string());
  ASSERT_EQ(run.wait(180).value_or(-1), 0) << test::readText(log.string());
  const std::string capture_log = test::readText((out / "logs" / "bmp-capture.log").string());
  EXPECT_EQ(capture_log.find("no answer on"), std::string::npos) << "lockstep stalled\n" << capture_log;
  EXPECT_NE(capture_log.find("published " + std::to_string(frames) + " frames"), std::string::npos)
      << capture_log;
  const std::string summary = test::readText((out / "summary.json").string());
  EXPECT_EQ(test::processFigure(summary, "bmp-tracker", "processed"), frames) << summary;
  EXPECT_EQ(test::processFigure(summary, "bmp-tracker", "lost"), 0) << summary;
  EXPECT_EQ(test::processFigure(summary, "bmp-detector", "lost"), 0) << summary;
}

}  // namespace
}  // namespace bmp

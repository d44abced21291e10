// The real bmp-tracker over LCM: Bonn frames in (lockstep), one SLAM_POSE per frame (a damaged one answered
// as skipped), keyframes with decodable images, the TUM trajectories written on SIGINT, and kept on SIGKILL.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <bmp/detections_t.hpp>
#include <bmp/keyframe_t.hpp>
#include <bmp/process_status_t.hpp>
#include <bmp/rgbd_frame_t.hpp>
#include <bmp/slam_pose_t.hpp>

#include "bmp/common/child_process.hpp"
#include "bmp/common/image_codec.hpp"
#include "bmp/common/stamp.hpp"
#include "bmp/common/tum_trajectory.hpp"
#include "bmp/lcm/conversions.hpp"
#include "bmp/lcm/lcm_node.hpp"
#include "capture/tum_sequence.hpp"
#include "file_image.hpp"
#include "forged_image.hpp"
#include "lcm_url.hpp"
#include "shared_data.hpp"

namespace bmp {
namespace {

camera_t bonnCamera() {
  camera_t c;
  c.width = 640;
  c.height = 480;
  c.fx = 542.822841;
  c.fy = 542.576870;
  c.cx = 315.593520;
  c.cy = 237.756098;
  const double d[5] = {0.039903, -0.099343, -0.000730, -0.000144, 0.0};
  for (int i = 0; i < 5; ++i) c.distortion[i] = d[i];
  return c;
}

// A bmp-tracker child on a test-unique udpm URL, and the test's own LCM node that feeds and watches it.
class TrackerUnderTest {
 public:
  // extra: more options for bmp-tracker, e.g. its frame policy.
  explicit TrackerUnderTest(const std::string& name, int slot, const std::vector<std::string>& extra = {})
      : url_(test::uniqueLcmUrl(slot)),
        dir_(test::scratchDir(name)),
        node_(url_),
        index_(capture::indexSequence(test::bonnDir())) {
    node_.subscribe<slam_pose_t>("SLAM_POSE",
                                 [this](const slam_pose_t& m, const ReceivedInfo&) { poses.push_back(m); });
    node_.subscribe<keyframe_t>("SLAM_KEYFRAME",
                                [this](const keyframe_t& m, const ReceivedInfo&) { keyframes.push_back(m); });
    node_.subscribe<process_status_t>("PROCESS_STATUS",
                                      [this](const process_status_t& m, const ReceivedInfo&) {
                                        heartbeat_ = heartbeat_ || m.name == "bmp-tracker";
                                      });
    std::vector<std::string> argv{test::binPath("bmp-tracker"),
                                  "--config",
                                  test::sourceDir() + "/config/tracker.yaml",
                                  "--lcm-url",
                                  url_,
                                  "--trajectory",
                                  trajectory(),
                                  "--keyframe-trajectory",
                                  keyframeTrajectory(),
                                  "--frame-log",
                                  frameLog()};
    argv.insert(argv.end(), extra.begin(), extra.end());
    child_ = std::make_unique<ChildProcess>(argv, ChildProcess::Output::kFile, logPath());
  }

  std::string trajectory() const { return (dir_ / "trajectory.txt").string(); }
  std::string keyframeTrajectory() const { return (dir_ / "keyframes.txt").string(); }
  std::string frameLog() const { return (dir_ / "frames.tsv").string(); }
  std::string logPath() const { return (dir_ / "bmp-tracker.log").string(); }
  ChildProcess& child() { return *child_; }

  bool pumpUntil(const std::function<bool()>& done, double timeout_s) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
    while (!done() && std::chrono::steady_clock::now() < end) node_.handle(20);
    return done();
  }
  bool ready() {
    return pumpUntil([&] { return heartbeat_ || !child_->running(); }, 30.0) && child_->running();
  }

  // Bonn frame i as bmp-capture publishes it, seq i.
  rgbd_frame_t frame(int i) const {
    const auto& pair = index_.frames[i];
    rgbd_frame_t msg;
    msg.seq = i;
    msg.utime = secondsToUtime(pair.rgb_stamp);
    msg.depth_utime = secondsToUtime(pair.depth_stamp);
    msg.source = "rgbd_bonn_crowd";
    msg.camera = bonnCamera();
    msg.depth_scale = 5000.0;
    msg.color = test::fileImage(pair.rgb_path, PixelFormat::kBgr8);
    msg.depth = test::fileImage(pair.depth_path, PixelFormat::kMono16);
    return msg;
  }

  template <typename Message>
  void publish(const std::string& channel, const Message& msg) {
    node_.publish(channel, msg);
  }

  // Publishes msg and waits for one more pose, as bmp-capture's lockstep does.
  bool publishAndWait(const rgbd_frame_t& msg) {
    const std::size_t before = poses.size();
    node_.publish("RGBD_FRAME", msg);
    return pumpUntil([&] { return poses.size() > before; }, 20.0);
  }

  // How another publisher might damage a frame's depth image.
  enum class Damage { kNone, kNotPng, kHugeHeader };
  // Publishes Bonn frame i and waits for its pose.
  bool playAndWait(int i, Damage damage = Damage::kNone) {
    rgbd_frame_t msg = frame(i);
    if (damage == Damage::kNotPng) msg.depth.data.assign(msg.depth.data.size(), 0x5a);
    // A well-formed PNG whose header claims 70000x70000: OpenCV threw on it, which once ended the tracker.
    if (damage == Damage::kHugeHeader) test::setPngSize(msg.depth.data, 70000, 70000);
    return publishAndWait(msg);
  }

  std::vector<slam_pose_t> poses;
  std::vector<keyframe_t> keyframes;

 private:
  std::string url_;
  std::filesystem::path dir_;
  LcmNode node_;
  capture::SequenceIndex index_;
  bool heartbeat_ = false;
  std::unique_ptr<ChildProcess> child_;
};

TEST(TrackerProcess, PosePerFrameKeyframesAndTrajectoryOnSigint) {
  TrackerUnderTest t("tracker_process", 0);
  ASSERT_TRUE(t.ready()) << "no heartbeat, or it exited; log " << t.logPath();
  const int n = 40;
  const int damaged = 20;  // undecodable depth: answered as skipped, tracking goes on
  const int bomb = 30;     // a depth header claiming a huge image: the same
  using Damage = TrackerUnderTest::Damage;
  for (int i = 0; i < n; ++i) {
    const Damage damage = i == damaged ? Damage::kNotPng : i == bomb ? Damage::kHugeHeader : Damage::kNone;
    ASSERT_TRUE(t.playAndWait(i, damage)) << "no pose for " << i << "; log " << t.logPath();
  }
  const std::vector<slam_pose_t>& poses = t.poses;
  const std::vector<keyframe_t>& kfs = t.keyframes;
  ASSERT_EQ(poses.size(), static_cast<std::size_t>(n));
  EXPECT_EQ(poses[damaged].seq, damaged);
  EXPECT_EQ(static_cast<int>(poses[damaged].state), static_cast<int>(slam_pose_t::STATE_SKIPPED));
  EXPECT_EQ(static_cast<int>(poses[bomb].state), static_cast<int>(slam_pose_t::STATE_SKIPPED));
  EXPECT_NE(test::readText(t.logPath()).find("png header says 70000x70000, declared 640x480 (not decoded)"),
            std::string::npos);
  for (int i = 0; i < n; ++i) {
    EXPECT_EQ(poses[i].seq, i);
    if (i == damaged || i == bomb) continue;
    EXPECT_EQ(static_cast<int>(poses[i].state), static_cast<int>(slam_pose_t::STATE_OK)) << "frame " << i;
    EXPECT_EQ(poses[i].num_keypoints, 1000);
    EXPECT_GT(poses[i].processing_ms, 0.0f);
    if (i > 0) {
      EXPECT_GT(poses[i].num_tracked, 100) << "frame " << i;
      // Hundreds of inliers over the room: millimetres.
      EXPECT_GT(poses[i].position_std_m, 0.0f) << "frame " << i;
      EXPECT_LT(poses[i].position_std_m, 0.02f) << "frame " << i;
    }
  }
  ASSERT_GE(kfs.size(), 1u);
  EXPECT_EQ(kfs[0].id, 0);
  EXPECT_EQ(kfs[0].seq, 0);
  const cv::Mat color = decodeImage(fromMsg(kfs[0].color));
  const cv::Mat depth = decodeImage(fromMsg(kfs[0].depth));
  const cv::Mat mask = decodeImage(fromMsg(kfs[0].dynamic_mask));
  EXPECT_EQ(color.type(), CV_8UC3);
  EXPECT_EQ(depth.type(), CV_16UC1);
  EXPECT_EQ(mask.type(), CV_8UC1);
  EXPECT_EQ(cv::countNonZero(mask), 0);

  EXPECT_EQ(t.child().stop(20.0), 0) << "log " << t.logPath();
  const Trajectory written = readTumTrajectory(t.trajectory());
  EXPECT_EQ(written.size(), static_cast<std::size_t>(n - 2));  // every frame but the skipped ones
  EXPECT_GE(readTumTrajectory(t.keyframeTrajectory()).size(), 1u);
  // The clean exit replaced the live file with the optimised trajectory.
  EXPECT_EQ(test::readFirstLine(t.trajectory()), "# timestamp tx ty tz qx qy qz qw");
}

// Killed without a chance to write (SIGKILL), the tracker still leaves every pose it had published.
TEST(TrackerProcess, KilledTrackerLeavesThePosesItPublished) {
  TrackerUnderTest t("tracker_killed", 1);
  ASSERT_TRUE(t.ready()) << "no heartbeat, or it exited; log " << t.logPath();
  const int n = 15;
  for (int i = 0; i < n; ++i) ASSERT_TRUE(t.playAndWait(i)) << "no pose for " << i;
  t.child().signal(SIGKILL);
  ASSERT_TRUE(t.child().wait(10).has_value());
  const Trajectory live = readTumTrajectory(t.trajectory());
  ASSERT_EQ(live.size(), static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    EXPECT_NEAR(live[i].stamp, t.poses[i].utime * 1e-6, 1e-6);
    EXPECT_LT((live[i].T_world_cam.translation() - fromMsg(t.poses[i].T_world_cam).translation()).norm(),
              1e-6);
  }
  EXPECT_NE(test::readFirstLine(t.trajectory()).find("live poses"), std::string::npos);
  EXPECT_GE(readTumTrajectory(t.keyframeTrajectory()).size(), 1u);
  // The frame log has a line for every answer heard, written before it, with the answer's counts.
  const auto rows = test::readTsvRows(t.frameLog());
  ASSERT_EQ(rows.size(), static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    ASSERT_GE(rows[i].size(), 16u) << "line " << i;
    EXPECT_EQ(rows[i][1], std::to_string(t.poses[i].seq));
    EXPECT_EQ(rows[i][2], "OK");
    EXPECT_EQ(rows[i][4], std::to_string(t.poses[i].num_tracked));
    EXPECT_EQ(rows[i][5], i == 0 ? "map_start" : i == 1 ? "reference" : "motion") << "line " << i;
    EXPECT_EQ(rows[i][14], "0");  // no frame missed before it
  }
}

// Two frames that never arrive (a gap in seq) do not throw the velocity away: the frame after them is
// tracked from the constant-velocity prediction scaled over the gap, as the frame log shows.
TEST(TrackerProcess, AfterFramesThatNeverArrivedTheMotionModelStillTracks) {
  TrackerUnderTest t("tracker_gap", 4);
  ASSERT_TRUE(t.ready()) << "no heartbeat, or it exited; log " << t.logPath();
  for (int i = 0; i < 26; ++i) {
    if (i == 20 || i == 21) continue;  // never published
    ASSERT_TRUE(t.playAndWait(i)) << "no pose for " << i;
  }
  EXPECT_EQ(t.child().stop(20.0), 0) << "log " << t.logPath();
  const auto rows = test::readTsvRows(t.frameLog());
  ASSERT_EQ(rows.size(), 24u);
  const auto& after = rows[20];  // seq 22
  ASSERT_GE(after.size(), 16u);
  EXPECT_EQ(after[1], "22");
  EXPECT_EQ(after[2], "OK");
  EXPECT_EQ(after[14], "2");                      // frames missed before it
  EXPECT_NEAR(std::stod(after[13]), 100.0, 5.0);  // 3 periods of Bonn's 30 Hz since the last frame, ms
  EXPECT_EQ(after[5], "motion");
  EXPECT_GT(std::stoi(after[6]), 100);  // the prediction kept plenty of the last frame's points
  for (std::size_t i = 2; i < rows.size(); ++i) EXPECT_EQ(rows[i][5], "motion") << "line " << i;
}

// A first frame whose camera is unusable (fx NaN or 0, depth scale 0) must not start a map with it: each is
// answered SKIPPED with the rule it broke, and the first good frame starts tracking.
TEST(TrackerProcess, UnusableFirstCameraIsRefusedWithTheReason) {
  TrackerUnderTest t("tracker_bad_first_camera", 2);
  ASSERT_TRUE(t.ready()) << "no heartbeat, or it exited; log " << t.logPath();
  rgbd_frame_t nan_fx = t.frame(0), zero_fx = t.frame(0), zero_scale = t.frame(0);
  nan_fx.camera.fx = std::nan("");
  zero_fx.camera.fx = 0;
  zero_scale.depth_scale = 0;
  const std::pair<rgbd_frame_t, const char*> bad[] = {{nan_fx, "camera intrinsics are not finite"},
                                                      {zero_fx, "focal length fx/fy must be positive"},
                                                      {zero_scale, "depth_scale must be positive"}};
  for (const auto& [msg, reason] : bad) {
    ASSERT_TRUE(t.publishAndWait(msg)) << reason;
    const slam_pose_t& answer = t.poses.back();
    EXPECT_EQ(static_cast<int>(answer.state), static_cast<int>(slam_pose_t::STATE_SKIPPED)) << reason;
    EXPECT_NE(answer.note.find(reason), std::string::npos) << answer.note;
  }
  for (int i = 0; i < 5; ++i) ASSERT_TRUE(t.playAndWait(i)) << "no pose for " << i;
  EXPECT_EQ(static_cast<int>(t.poses.back().state), static_cast<int>(slam_pose_t::STATE_OK));
  EXPECT_EQ(t.child().stop(20.0), 0);
  // Only the good frames' poses, with the real camera: none of the refused ones started the map.
  EXPECT_EQ(readTumTrajectory(t.trajectory()).size(), 5u);
  const std::string log = test::readText(t.logPath());
  EXPECT_NE(log.find("fx 542.823"), std::string::npos) << log;
}

// Mid-run, a frame of another camera and a frame whose stamp goes back are refused with the reason; the
// real frames after them are tracked as before.
TEST(TrackerProcess, CameraChangeAndStampsOutOfOrderAreRefused) {
  TrackerUnderTest t("tracker_midrun_refusals", 3);
  ASSERT_TRUE(t.ready()) << "no heartbeat, or it exited; log " << t.logPath();
  for (int i = 0; i < 10; ++i) ASSERT_TRUE(t.playAndWait(i)) << "no pose for " << i;
  rgbd_frame_t other = t.frame(10);
  other.camera.fx *= 1.5;  // another lens: the map's scale would be wrong with it
  ASSERT_TRUE(t.publishAndWait(other));
  EXPECT_EQ(static_cast<int>(t.poses.back().state), static_cast<int>(slam_pose_t::STATE_SKIPPED));
  EXPECT_NE(t.poses.back().note.find("camera changed mid-run"), std::string::npos) << t.poses.back().note;
  rgbd_frame_t back = t.frame(10);
  back.utime = t.frame(3).utime;  // the next seq, with an old stamp
  ASSERT_TRUE(t.publishAndWait(back));
  EXPECT_EQ(static_cast<int>(t.poses.back().state), static_cast<int>(slam_pose_t::STATE_SKIPPED));
  EXPECT_NE(t.poses.back().note.find("stamp is not after"), std::string::npos) << t.poses.back().note;
  const std::size_t answered = t.poses.size();
  t.publish("RGBD_FRAME", t.frame(5));  // an old frame replayed: it had its answer, and gets no other
  for (int i = 10; i < 15; ++i) {
    ASSERT_TRUE(t.playAndWait(i)) << "no pose for " << i;
    EXPECT_EQ(t.poses.back().seq, i);
    EXPECT_EQ(static_cast<int>(t.poses.back().state), static_cast<int>(slam_pose_t::STATE_OK)) << i;
  }
  EXPECT_EQ(t.poses.size(), answered + 5);
  EXPECT_EQ(t.child().stop(20.0), 0);
  const Trajectory written = readTumTrajectory(t.trajectory());
  ASSERT_EQ(written.size(), 15u);  // in time order, none of the refused frames
  for (std::size_t i = 1; i < written.size(); ++i) EXPECT_GT(written[i].stamp, written[i - 1].stamp);
}

// One forged frame of another camera, far ahead in seq, before capture's first: it must not lock the real
// camera out. The real frames replace its camera, the map started from it is dropped, and none of its
// keyframes reaches the mapper: every keyframe sent has the real camera, the first with id 0, and the live
// trajectory file holds only the real camera's poses.
TEST(TrackerProcess, AForgedFirstFrameOfAnotherCameraIsReplacedByTheReal) {
  TrackerUnderTest t("tracker_forged_first_frame", 5);
  ASSERT_TRUE(t.ready()) << "no heartbeat, or it exited; log " << t.logPath();
  rgbd_frame_t forged = t.frame(0);
  forged.seq = 900;
  forged.camera.fx *= 1.5;
  ASSERT_TRUE(t.publishAndWait(forged));
  for (int i = 0; i < 10; ++i) {
    ASSERT_TRUE(t.playAndWait(i)) << "no pose for " << i;
    EXPECT_EQ(static_cast<int>(t.poses.back().state), static_cast<int>(slam_pose_t::STATE_OK)) << i;
  }
  // The live file, read while the tracker runs (as a planner would), holds no pose of the dropped map.
  const Trajectory live = readTumTrajectory(t.trajectory());
  ASSERT_EQ(live.size(), 10u);
  EXPECT_NEAR(live.front().stamp, utimeToSeconds(t.frame(0).utime), 1e-6);
  EXPECT_EQ(t.child().stop(20.0), 0);
  // Keyframes wait for their boxes (no detector here) until the hold is up or the tracker stops.
  ASSERT_TRUE(t.pumpUntil([&] { return !t.keyframes.empty(); }, 5.0));
  EXPECT_EQ(t.keyframes.front().id, 0);
  for (const keyframe_t& kf : t.keyframes) EXPECT_DOUBLE_EQ(kf.camera.fx, bonnCamera().fx) << kf.id;
  const Trajectory written = readTumTrajectory(t.trajectory());
  ASSERT_EQ(written.size(), 10u);  // the real frames only
  EXPECT_NEAR(written.front().stamp, utimeToSeconds(t.frame(0).utime), 1e-6);
  const std::string log = test::readText(t.logPath());
  EXPECT_NE(log.find("which came with only 1 message(s); starting again with this one"), std::string::npos)
      << log;
  EXPECT_NE(log.find("dropping the map of 1 keyframe(s) (1 not yet sent to the mapper)"), std::string::npos)
      << log;
}

// The same, with the real camera's first frame dropped from the tracker's queue: the forged frame, 4096x4096,
// keeps the tracker busy while a burst of real frames overflows its queue (4 frames). The frame whose camera
// replaced the forged one was among those dropped; the frames tracked must still start a map of their own,
// not go on in the forged camera's (whose size is not even theirs).
TEST(TrackerProcess, ACameraReplacedInAFrameDroppedFromTheQueueStillStartsANewMap) {
  TrackerUnderTest t("tracker_forged_first_frame_dropped", 7);
  ASSERT_TRUE(t.ready()) << "no heartbeat, or it exited; log " << t.logPath();
  rgbd_frame_t forged = t.frame(0);
  forged.seq = 900;
  forged.camera.width = 4096;  // the largest image a frame may hold: slow to take
  forged.camera.height = 4096;
  forged.camera.cx = 2048;
  forged.camera.cy = 2048;
  for (double& d : forged.camera.distortion) d = 0.0;  // Bonn's lens would fold over inside so wide an image
  forged.color =
      toMsg(encodeImage(cv::Mat(4096, 4096, CV_8UC3, cv::Scalar(90, 120, 150)), ImageEncoding::kPng));
  forged.depth = toMsg(encodeImage(cv::Mat(4096, 4096, CV_16UC1, cv::Scalar(10000)), ImageEncoding::kPng));
  t.publish("RGBD_FRAME", forged);
  const int burst = 8;
  for (int i = 0; i < burst; ++i) t.publish("RGBD_FRAME", t.frame(i));
  ASSERT_TRUE(t.pumpUntil([&] { return !t.poses.empty() && t.poses.back().seq == burst - 1; }, 60.0))
      << "no pose for the burst's last frame; log " << t.logPath();
  EXPECT_EQ(t.child().stop(20.0), 0);
  t.pumpUntil([&] { return false; }, 1.0);  // the held keyframes, sent as the tracker stops
  const std::string log = test::readText(t.logPath());
  // The case this test is about: real frames, the first of them among them, gave way in the queue.
  EXPECT_EQ(log.find(" 0 dropped while busy"), std::string::npos) << log;
  std::vector<int64_t> tracked;
  for (const slam_pose_t& p : t.poses)
    if (p.seq < burst) tracked.push_back(p.seq);
  ASSERT_GE(tracked.size(), 3u) << log;
  EXPECT_GT(tracked.front(), 0) << "the first real frame was tracked; it should have been dropped. " << log;
  for (const slam_pose_t& p : t.poses) {
    if (p.seq == 900) continue;  // the forged frame's own answer
    EXPECT_EQ(static_cast<int>(p.state), static_cast<int>(slam_pose_t::STATE_OK)) << p.seq << ": " << p.note;
  }
  // The forged frame's featureless image started no keyframe, but the tracker was made with its camera.
  EXPECT_NE(log.find("dropping the map of 0 keyframe(s)"), std::string::npos) << log;
  EXPECT_NE(log.find("camera 640x480 fx 542.823 from rgbd_bonn_crowd"), std::string::npos) << log;
  ASSERT_FALSE(t.keyframes.empty()) << log;
  for (const keyframe_t& kf : t.keyframes) {
    EXPECT_DOUBLE_EQ(kf.camera.fx, bonnCamera().fx) << kf.id;
    EXPECT_EQ(kf.camera.width, 640) << kf.id;
  }
  const Trajectory written = readTumTrajectory(t.trajectory());
  ASSERT_EQ(written.size(), tracked.size());  // the real frames only
  EXPECT_NEAR(written.front().stamp, utimeToSeconds(t.frame(static_cast<int>(tracked.front())).utime), 1e-6);
}

// Answers from another publisher: one for an image of another size, one naming a frame already heard with
// another stamp. Each is refused with the reason (counted as malformed), and tracking goes on. The
// detector's own answer for a frame it could not read (skipped, no boxes, no image size) is not refused.
TEST(TrackerProcess, DetectionAnswersOfAnotherImageOrStampAreRefused) {
  TrackerUnderTest t("tracker_forged_answers", 4);
  ASSERT_TRUE(t.ready()) << "no heartbeat, or it exited; log " << t.logPath();
  for (int i = 0; i < 5; ++i) ASSERT_TRUE(t.playAndWait(i)) << "no pose for " << i;
  detections_t wrong_size{};
  wrong_size.seq = 4;
  wrong_size.utime = t.frame(4).utime;
  wrong_size.model = "forged";
  wrong_size.image_width = 320;
  wrong_size.image_height = 240;
  detections_t wrong_stamp = wrong_size;
  wrong_stamp.utime += 1;
  wrong_stamp.image_width = 640;
  wrong_stamp.image_height = 480;
  detections_t skipped{};
  skipped.seq = 5;
  skipped.utime = t.frame(5).utime;
  skipped.model = "yolov5n_coco_320";
  skipped.skipped = "colour image: not a PNG";  // as bmp-detector answers: image size 0x0
  t.publish("DETECTIONS", wrong_size);
  t.publish("DETECTIONS", wrong_stamp);
  t.publish("DETECTIONS", skipped);
  for (int i = 5; i < 8; ++i) ASSERT_TRUE(t.playAndWait(i)) << "no pose for " << i;
  EXPECT_EQ(static_cast<int>(t.poses.back().state), static_cast<int>(slam_pose_t::STATE_OK));
  EXPECT_EQ(t.child().stop(20.0), 0);
  const std::string log = test::readText(t.logPath());
  EXPECT_NE(log.find("answer for frame 4 is for a 320x240 image, the camera's is 640x480"), std::string::npos)
      << log;
  EXPECT_NE(log.find("answer for frame 4 has stamp " + std::to_string(wrong_stamp.utime) + " us"),
            std::string::npos)
      << log;
  EXPECT_EQ(log.find("answer for frame 5"), std::string::npos) << log;
}

// The detector's answer for Bonn frame i: one person box, or none.
detections_t answerFor(const rgbd_frame_t& frame, bool person) {
  detections_t d{};
  d.seq = frame.seq;
  d.utime = frame.utime;
  d.model = "yolov5n_coco_320";
  d.image_width = 640;
  d.image_height = 480;
  if (person) {
    detection_t b{};
    b.x = 200;
    b.y = 100;
    b.width = 160;
    b.height = 300;
    b.class_id = 0;
    b.label = "person";
    b.score = 0.9f;
    b.dynamic_level = detection_t::LEVEL_HIGH;
    d.detections.push_back(b);
  }
  d.num_detections = static_cast<int32_t>(d.detections.size());
  return d;
}

// Lockstep with no detector on the bus waits for boxes once, then tracks without them until one is heard.
// A stray answer that is refused (another stamp for a frame) is no detector heard: counted as heard, it put
// the 3 s wait back on every frame (found by review).
TEST(TrackerProcess, ARefusedStrayAnswerDoesNotPutTheLockstepWaitBack) {
  TrackerUnderTest t("tracker_stray_answer", 0, {"--frame-policy", "every"});
  ASSERT_TRUE(t.ready()) << "no heartbeat, or it exited; log " << t.logPath();
  const rgbd_frame_t first = t.frame(0);
  ASSERT_TRUE(t.publishAndWait(first));  // waits detections_wait_ms (3 s) once, then warns
  detections_t stray = answerFor(first, false);
  stray.utime += 1;  // not the frame's stamp: refused
  t.publish("DETECTIONS", stray);
  t.pumpUntil([] { return false; }, 0.3);
  const auto start = std::chrono::steady_clock::now();
  for (int i = 1; i <= 3; ++i) ASSERT_TRUE(t.playAndWait(i)) << "no pose for " << i;
  const double took = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_LT(took, 6.0) << "three frames waited for boxes again (3 s each)";
  EXPECT_EQ(t.child().stop(20.0), 0);
  EXPECT_NE(test::readText(t.logPath()).find("answer for frame 0 has stamp"), std::string::npos);
}

// Lockstep capture sends a frame again when its pose is slow to come, and the detector answers it again.
// The first keyframe, held until the camera settles, took its boxes when it was tracked: the answer again
// is no news. It was taken as the keyframe's late boxes, applied a second time (runs differed).
TEST(TrackerProcess, AnAnswerForAFrameSentAgainIsNotTakenAsLateBoxes) {
  TrackerUnderTest t("tracker_answer_again", 8);
  ASSERT_TRUE(t.ready()) << "no heartbeat, or it exited; log " << t.logPath();
  const rgbd_frame_t first = t.frame(0);
  t.publish("DETECTIONS", answerFor(first, true));
  ASSERT_TRUE(t.publishAndWait(first)) << "no pose for 0";
  ASSERT_TRUE(t.publishAndWait(first)) << "no pose for 0 sent again";
  t.publish("DETECTIONS", answerFor(first, true));  // the same answer again
  for (int i = 1; i < 8; ++i) {
    const rgbd_frame_t msg = t.frame(i);
    t.publish("DETECTIONS", answerFor(msg, false));
    ASSERT_TRUE(t.publishAndWait(msg)) << "no pose for " << i;
  }
  ASSERT_TRUE(t.pumpUntil([&] { return !t.keyframes.empty(); }, 10.0)) << "keyframe 0 never released";
  EXPECT_EQ(t.keyframes.front().id, 0);
  EXPECT_EQ(t.child().stop(20.0), 0);
  const std::string log = test::readText(t.logPath());
  EXPECT_NE(log.find("tracked 8 frames"), std::string::npos) << log;
  EXPECT_EQ(log.find("took theirs late"), std::string::npos) << log;
  EXPECT_EQ(log.find("answer for frame 0"), std::string::npos) << "the same answer is no error\n" << log;
}

// Another publisher's frame, refused, comes between a frame and lockstep capture sending that frame again
// (its pose was slow): the resend is still answered with the frame's pose. The refusal's answer took the
// place of the frame's, and capture waited for an answer that never came.
TEST(TrackerProcess, ARefusedFrameDoesNotReplaceTheAnswerAResendRepeats) {
  TrackerUnderTest t("tracker_refused_between", 9);
  ASSERT_TRUE(t.ready()) << "no heartbeat, or it exited; log " << t.logPath();
  for (int i = 0; i < 3; ++i) ASSERT_TRUE(t.playAndWait(i)) << "no pose for " << i;
  rgbd_frame_t forged = t.frame(3);
  forged.depth_scale = 0.0;
  ASSERT_TRUE(t.publishAndWait(forged));
  EXPECT_EQ(static_cast<int>(t.poses.back().state), static_cast<int>(slam_pose_t::STATE_SKIPPED));
  ASSERT_TRUE(t.publishAndWait(t.frame(2))) << "the resend of frame 2 was not answered";
  EXPECT_EQ(t.poses.back().seq, 2);
  EXPECT_EQ(t.poses.back().utime, t.frame(2).utime);
  EXPECT_NE(static_cast<int>(t.poses.back().state), static_cast<int>(slam_pose_t::STATE_SKIPPED));
  EXPECT_TRUE(t.publishAndWait(forged)) << "a refused frame sent again is answered again";
  EXPECT_EQ(t.child().stop(20.0), 0);
}

// Another publisher's damaged copy of a frame just tracked (the same seq and stamp) is refused without a
// skipped pose in the frame's name: lockstep capture would take it as the frame's answer.
TEST(TrackerProcess, ADamagedCopyOfAFrameIsNotAnsweredInItsName) {
  TrackerUnderTest t("tracker_damaged_copy", 12);
  ASSERT_TRUE(t.ready()) << "no heartbeat, or it exited; log " << t.logPath();
  for (int i = 0; i < 4; ++i) {
    ASSERT_TRUE(t.playAndWait(i)) << "no pose for " << i;
    rgbd_frame_t copy = t.frame(i);
    copy.camera.fx = -1.0;
    t.publish("RGBD_FRAME", copy);
  }
  ASSERT_TRUE(t.playAndWait(4)) << "no pose for 4";
  EXPECT_EQ(t.child().stop(20.0), 0);
  t.pumpUntil([] { return false; }, 0.5);  // anything still in flight
  ASSERT_EQ(t.poses.size(), 5u) << "a copy was answered";
  for (int i = 0; i < 5; ++i) {
    EXPECT_EQ(t.poses[i].seq, i);
    EXPECT_NE(static_cast<int>(t.poses[i].state), static_cast<int>(slam_pose_t::STATE_SKIPPED)) << i;
  }
  const std::string log = test::readText(t.logPath());
  EXPECT_NE(log.find("frame seq 3: "), std::string::npos) << log;
  EXPECT_NE(log.find("(a damaged copy of a frame taken; not answered)"), std::string::npos) << log;
}

// Found by review: an exact replay of a frame answered before was answered again as 'skipped' under its name;
// one refused frame of another camera with seq 9010 counted 9000 frames lost and hid the real losses after
// it; the frame log's 'missed' column took gaps of frames received after the frame it was written for.
TEST(TrackerProcess, ReplaysAndForeignFramesMoveNoAnswerAndNoCountOfLostFrames) {
  TrackerUnderTest t("tracker_replay_foreign", 13);
  ASSERT_TRUE(t.ready()) << "no heartbeat, or it exited; log " << t.logPath();
  for (int i = 0; i < 10; ++i) ASSERT_TRUE(t.playAndWait(i)) << "no pose for " << i;  // the camera settles
  rgbd_frame_t foreign = t.frame(10);
  foreign.seq = 9010;
  foreign.camera.fx = 600.0;
  ASSERT_TRUE(t.publishAndWait(foreign));  // refused, and answered: it names no frame taken
  EXPECT_EQ(static_cast<int>(t.poses.back().state), static_cast<int>(slam_pose_t::STATE_SKIPPED));
  t.publish("RGBD_FRAME", t.frame(5));  // a replay: not answered
  ASSERT_TRUE(t.playAndWait(10));
  ASSERT_TRUE(t.playAndWait(14));  // 11 to 13 never sent
  EXPECT_EQ(t.child().stop(20.0), 0) << "log " << t.logPath();
  t.pumpUntil([] { return false; }, 0.5);  // anything still in flight
  ASSERT_EQ(t.poses.size(), 13u);
  int answers_for_5 = 0;
  for (const auto& p : t.poses) answers_for_5 += p.seq == 5;
  EXPECT_EQ(answers_for_5, 1);
  const auto rows = test::readTsvRows(t.frameLog());
  ASSERT_EQ(rows.size(), 12u);
  EXPECT_EQ(rows[10][1], "10");
  EXPECT_EQ(rows[10][14], "0");
  EXPECT_EQ(rows[11][1], "14");
  EXPECT_EQ(rows[11][14], "3");
  const std::string log = test::readText(t.logPath());
  EXPECT_NE(log.find("seq 5 does not follow 9 (a copy of a frame taken before; not answered)"),
            std::string::npos)
      << log;
  EXPECT_NE(log.find("3 frame(s) never arrived"), std::string::npos) << log;
  EXPECT_EQ(log.find("9000 frame(s)"), std::string::npos) << log;
}

// A run that stops before its camera settled sends no keyframe to the mapper, at exit as during the run:
// the frames may be a forged sender's (found by review: the exit sent them).
TEST(TrackerProcess, AtExitKeyframesOfAnUnsettledCameraAreNotSent) {
  TrackerUnderTest t("tracker_unsettled_exit", 14);
  ASSERT_TRUE(t.ready()) << "no heartbeat, or it exited; log " << t.logPath();
  ASSERT_TRUE(t.playAndWait(0));
  EXPECT_EQ(t.child().stop(20.0), 0) << "log " << t.logPath();
  t.pumpUntil([] { return false; }, 1.0);
  EXPECT_TRUE(t.keyframes.empty());
  EXPECT_NE(
      test::readText(t.logPath()).find("1 keyframe(s) of a camera that never settled not sent to the mapper"),
      std::string::npos);
}

// --idle-exit counts from the last frame received, taken or refused: with only refused frames (no map ever
// started) it never fired (found by review).
TEST(TrackerProcess, IdleExitAlsoAfterOnlyRefusedFrames) {
  TrackerUnderTest t("tracker_idle_refused", 15, {"--idle-exit", "1"});
  ASSERT_TRUE(t.ready()) << "no heartbeat, or it exited; log " << t.logPath();
  rgbd_frame_t bad = t.frame(0);
  bad.camera.fx = std::nan("");
  ASSERT_TRUE(t.publishAndWait(bad));
  EXPECT_EQ(static_cast<int>(t.poses.back().state), static_cast<int>(slam_pose_t::STATE_SKIPPED));
  const std::optional<int> status = t.child().wait(20);
  ASSERT_TRUE(status.has_value()) << "still running; log " << t.logPath();
  EXPECT_EQ(*status, 0);
  EXPECT_NE(test::readText(t.logPath()).find("no frame for 1 s: finishing"), std::string::npos);
}

// A capture restarted (seq from 0 again, after frames up to seq 2009): answers are judged "far ahead"
// against the new stream. Against the old stream's seq (the largest seen, as before), a forged answer for
// seq 1500 was taken, and with others like it would have pushed the real answers out of the book.
TEST(TrackerProcess, AfterACaptureRestartAnswersAreJudgedAgainstTheNewStream) {
  TrackerUnderTest t("tracker_restart_answers", 6);
  ASSERT_TRUE(t.ready()) << "no heartbeat, or it exited; log " << t.logPath();
  for (int i = 0; i < 10; ++i) {
    rgbd_frame_t msg = t.frame(i);
    msg.seq = 2000 + i;
    ASSERT_TRUE(t.publishAndWait(msg)) << "no pose for " << i;
  }
  for (int i = 10; i < 20;
       ++i) {  // the restarted capture: seq 0 on, its first frames refused until it resyncs
    rgbd_frame_t msg = t.frame(i);
    msg.seq = i - 10;
    ASSERT_TRUE(t.publishAndWait(msg)) << "no pose for " << i;
  }
  EXPECT_EQ(static_cast<int>(t.poses.back().state), static_cast<int>(slam_pose_t::STATE_OK));
  detections_t forged{};
  forged.seq = 1500;
  forged.utime = t.frame(19).utime + 1000000;
  forged.model = "forged";
  forged.image_width = 640;
  forged.image_height = 480;
  t.publish("DETECTIONS", forged);
  for (int i = 20; i < 23; ++i) {
    rgbd_frame_t msg = t.frame(i);
    msg.seq = i - 10;
    ASSERT_TRUE(t.publishAndWait(msg)) << "no pose for " << i;
  }
  EXPECT_EQ(t.child().stop(20.0), 0);
  const std::string log = test::readText(t.logPath());
  EXPECT_NE(log.find("answer for frame 1500, far ahead of the newest frame 9"), std::string::npos) << log;
}

// Keyframes reach the mapper in id order, whatever holds one back. The first is held until the stream's
// camera settles, and was then kept keyframe_hold_ms more for late boxes though it had its own (in lockstep,
// too): a keyframe made meanwhile went out at once, ahead of it, and the mapper took keyframe 0 coming after
// keyframe 1 as the start of a new map. Both frame policies, every frame answered (no boxes) before it comes.
TEST(TrackerProcess, KeyframesGoOutInIdOrder) {
  const int n = 60;
  int slot = 10;
  for (const std::string policy : {"every", "latest"}) {
    SCOPED_TRACE("frame policy " + policy);
    TrackerUnderTest t("tracker_keyframe_order_" + policy, slot++, {"--frame-policy", policy});
    ASSERT_TRUE(t.ready()) << "no heartbeat, or it exited; log " << t.logPath();
    for (int i = 0; i < n; ++i) {
      const rgbd_frame_t msg = t.frame(i);
      t.publish("DETECTIONS", answerFor(msg, false));
      ASSERT_TRUE(t.publishAndWait(msg)) << "no pose for " << i;
    }
    EXPECT_EQ(t.child().stop(20.0), 0) << "log " << t.logPath();
    t.pumpUntil([] { return false; }, 1.0);  // the keyframes released on the stop
    ASSERT_GE(t.keyframes.size(), 3u) << "too few keyframes to show an order; log " << t.logPath();
    EXPECT_EQ(t.keyframes.front().id, 0);
    for (std::size_t k = 1; k < t.keyframes.size(); ++k)
      EXPECT_GT(t.keyframes[k].id, t.keyframes[k - 1].id) << "keyframe " << k << " heard";
  }
}

}  // namespace
}  // namespace bmp

#pragma once
// bmp-tracker's LCM side: a receive thread drains the LCM socket, checks each frame against the stream
// (frame_checks.hpp: sequence gaps counted as lost there, before the queue) and puts it in a bounded queue
// (the oldest waiting frame gives way, counted as dropped), so a slow frame becomes a counted drop here
// instead of a silent loss in the kernel's buffer, and no frame is counted twice. The main thread tracks
// each frame and publishes the results. The process's main only reads configuration and runs it.
#include <atomic>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include <bmp/detections_t.hpp>
#include <bmp/rgbd_frame_t.hpp>
#include <bmp/slam_pose_t.hpp>

#include "bmp/common/bounded_queue.hpp"
#include "bmp/common/timing.hpp"
#include "bmp/common/tum_trajectory.hpp"
#include "bmp/common/warning_throttle.hpp"
#include "bmp/lcm/camera_pin.hpp"
#include "bmp/lcm/frame_checks.hpp"
#include "bmp/lcm/last_answer.hpp"
#include "bmp/lcm/process.hpp"
#include "tracker/detection_book.hpp"
#include "tracker/frame_log.hpp"
#include "tracker/tracker.hpp"
#include "tracker/tracker_options.hpp"
#include "tracker/tracker_settings.hpp"

namespace bmp::tracker {

struct TrackerChannels {
  std::string frames = channels::kFrames;
  std::string pose = channels::kPose;
  std::string keyframe = channels::kKeyframe;
  std::string keyframe_poses = channels::kKeyframePoses;
  std::string detections = channels::kDetections;
};

// Where the trajectories go (empty: not written). Each is written pose by pose while tracking, so a killed
// process leaves what it had, and replaced whole by the optimised one at a clean exit.
struct TrackerOutputs {
  std::string trajectory;
  std::string keyframe_trajectory;
  std::string frame_log;  // one line per frame tracked (frame_log.hpp)
};

class TrackerNode {
 public:
  // Opens the outputs at once: an unwritable path fails at start-up, naming it (TrajectoryError).
  TrackerNode(ProcessContext& ctx, TrackerConfig config, TrackerChannels channels, std::size_t queue_capacity,
              const TrackerOutputs& outputs, DetectionPolicy policy = {});
  ~TrackerNode();  // stops the receive thread
  TrackerNode(const TrackerNode&) = delete;
  TrackerNode& operator=(const TrackerNode&) = delete;

  // Until a stop is requested, or idle_exit_s (> 0) seconds pass without a frame after the first.
  void run(double idle_exit_s);
  // Replaces the live files with the trajectories after local mapping's corrections; call after run().
  void writeTrajectories();

 private:
  // A frame with the stream's verdict on it, given on the receive thread.
  struct Queued {
    rgbd_frame_t msg;
    FrameStream::Verdict verdict;
  };
  void receive();                                                             // the receive thread's loop
  void onFrame(const rgbd_frame_t& msg);                                      // on the receive thread
  void refuse(const rgbd_frame_t& msg, const FrameStream::Verdict& verdict);  // likewise
  void process(const Queued& frame);
  void onDetections(const detections_t& msg);
  // The frame's boxes: its own answer, or in real time the newest earlier ones moved on for their age.
  struct FrameBoxChoice {
    std::optional<std::vector<ObjectBox>> boxes;  // none: the frame is tracked on its priors alone
    bool own = false;                             // the frame's own answer (not a stand-in)
  };
  FrameBoxChoice boxesFor(const rgbd_frame_t& msg);
  void logFrame(const TrackResult& r, int64_t missed, const FrameBoxChoice& choice);
  // Real time: publishes held keyframes whose answer came (with late boxes applied) or whose time is up.
  void releaseHeldKeyframes(bool all);
  void publish(const rgbd_frame_t& msg, const TrackResult& r, const cv::Mat& color, const cv::Mat& depth,
               bool had_boxes);
  // Answers a frame that cannot be tracked with STATE_SKIPPED and the reason, warns and counts it.
  void skip(const rgbd_frame_t& msg, const std::string& reason);
  void syncStatus();  // the receive thread's counts into the heartbeat (main thread only)
  // The stream's camera replaced an unsettled one (a forged first frame's): the map built from its frames
  // is dropped, with the keyframes held back from the mapper, and tracking starts again.
  void startAgainForNewCamera();

  ProcessContext& ctx_;
  TrackerConfig config_;
  TrackerChannels channels_;
  BoundedQueue<Queued> queue_;
  std::atomic<bool> receiving_{true};
  // The receive thread's counts, read by the main thread for the heartbeat.
  std::atomic<int64_t> received_{0}, lost_before_{0}, refused_{0}, refusals_answered_{0};
  std::mutex refusal_mutex_;
  std::string last_refusal_;  // guarded by refusal_mutex_
  WarningThrottle warnings_;  // a flood of bad frames cannot flood the log (both threads)
  int64_t received_reported_ = 0, dropped_reported_ = 0, lost_reported_ = 0, refused_reported_ = 0,
          answered_reported_ = 0;
  FrameStream stream_;        // receive thread only
  int64_t dropped_seen_ = 0;  // dropped from the queue when the last frame was tracked
  int64_t degraded_ = 0;      // OK poses published as DEGRADED
  DetectionPolicy policy_;
  DetectionBook book_;
  LastAnswer<slam_pose_t> last_pose_;  // published again for a repeated frame
  int64_t newest_frame_seq_ = 0;       // receive thread only: answers far beyond it name no frame of ours
  static constexpr int64_t kAnswersAhead = 30;  // how far beyond it an answer may name a frame (lost here)
  std::atomic<int64_t> detections_heard_{0};
  bool warned_no_detections_ = false;
  struct HeldKeyframe {
    rgbd_frame_t frame;
    cv::Mat color, depth;
    KeyFramePose keyframe;
    cv::Mat mask;
    bool awaits_boxes = false;  // real time, made without its own boxes: they may come yet
    Stopwatch held;
  };
  std::deque<HeldKeyframe> held_;
  // Keyframes are held back until the stream's camera settles, so a forged first frame's never reach the
  // mapper (it keeps keyframes by id, and the map started again reuses the ids).
  bool camera_settled_ = false;
  int64_t late_applied_ = 0;
  int64_t stale_boxes_used_ = 0;  // frames observed with an earlier frame's boxes
  std::unique_ptr<Tracker> tracker_;
  // The camera tracker_ was made with. The frame whose camera replaced it (verdict.new_camera) may have been
  // dropped from the queue, so each tracked frame's camera is compared with it, not only that flag.
  CameraPin map_camera_{1};
  TrackerOutputs outputs_;
  std::optional<TumTrajectoryStream> live_trajectory_;
  std::optional<TumTrajectoryStream> live_keyframes_;
  std::optional<FrameLog> frame_log_;
  TimingStats timing_;
  int64_t lost_ = 0;
  std::thread receiver_;  // last: started once everything it uses exists
};

}  // namespace bmp::tracker

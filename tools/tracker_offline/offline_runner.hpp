#pragma once
// Runs the tracker over frames without LCM, for tests and benchmarks: from a TUM-format folder or any
// frame provider. Image loading is not timed; tracking is.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "bmp/common/timing.hpp"
#include "bmp/common/tum_trajectory.hpp"
#include "tracker/tracker.hpp"

namespace bmp::tracker {

struct OfflineFrame {
  double stamp = 0.0;
  cv::Mat image;                                // BGR or gray
  cv::Mat depth;                                // CV_16UC1 or CV_32FC1 metres
  cv::Mat mover_mask;                           // optional CV_8UC1: nonzero on things that move (the truth)
  std::optional<std::vector<ObjectBox>> boxes;  // the detector's, when known (the dynamic stage's input)
  // An answer that comes with this frame for the frame `frames_back` before it (real time: boxes that
  // arrive after their frame was tracked), applied to the keyframe that frame made, if it made one.
  struct LateBoxes {
    int frames_back = 1;
    std::vector<ObjectBox> boxes;
  };
  std::optional<LateBoxes> late;
  bool boxes_stand_in = false;  // boxes: an earlier frame's answer standing in for this one's (real time)
};
// Returns the next frame, or nullopt at the end.
using FrameProvider = std::function<std::optional<OfflineFrame>()>;

struct OfflineOptions {
  int max_frames = -1;  // <0: all
  // Called after each frame with its result and the frame itself (e.g. progress output, scoring).
  std::function<void(const TrackResult&, const OfflineFrame&)> on_result;
  bool exclude_movers = false;  // the frames' mover masks exclude keypoints: an oracle dynamic stage
  bool keep_results = true;     // false: OfflineResult::results stays empty (long runs that measure memory)
};

struct OfflineResult {
  Trajectory trajectory;  // Tracker::trajectory() after finish()
  Trajectory keyframe_trajectory;
  std::vector<TrackResult> results;  // one per frame, in order
  TimingStats track_ms;              // Tracker::track per frame
  int frames = 0;
  int frames_lost = 0;          // frames whose state was LOST
  int gap_rechecks = 0;         // frames whose motion-model pose was checked after a gap (tracking.recheck_*)
  int gap_reference_taken = 0;  // ... and tracked from the reference keyframe instead
  bool lost_at_end = false;
};

OfflineResult runOffline(Tracker& tracker, const FrameProvider& next, const OfflineOptions& options = {});

struct TumFolderOptions {
  int start = 0;                      // the first frame pair played
  Trajectory* groundtruth = nullptr;  // receives the folder's ground truth when not null
  // DIR/mask/<rgb file name> (as bmp-synth writes it) is each frame's mover mask; a frame without one is an
  // error naming the file.
  bool load_masks = false;
  // False leaves the folder's problems unsaid: for a second reading of a folder already read aloud.
  bool warn = true;
};

// Frames of a TUM-format folder (rgb.txt, depth.txt, associated by bmp::capture::indexSequence), read by
// bmp-capture's reader (capture::TumSource): a pair with a file missing, corrupt or not the camera's size
// and format is skipped with a warning on stderr naming the file.
FrameProvider tumFolderFrames(const std::string& dir, const CameraIntrinsics& camera,
                              const TumFolderOptions& options = {});

}  // namespace bmp::tracker

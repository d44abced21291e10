#pragma once
// bmp-capture's LCM side: opens the frame source, holds the first frame until the --wait-for processes are
// heard, plays every frame through the FramePlayer and writes the ground truth: a dataset's before the first
// frame, a synthetic scene's pose by pose as it plays, so a capture that dies mid-run still leaves the
// ground truth of every frame it published. The process's main only reads the settings and runs it.
#include <memory>
#include <string>

#include "bmp/common/tum_trajectory.hpp"
#include "bmp/common/warning_throttle.hpp"

#include "bmp/lcm/process.hpp"
#include "capture/capture_settings.hpp"
#include "capture/frame_source.hpp"
#include "capture/lcm/frame_player.hpp"

namespace bmp::capture {

class CaptureNode {
 public:
  // Opens the source at once: a missing folder, an unknown camera or a bad scene file fails at start-up.
  CaptureNode(ProcessContext& ctx, CaptureSettings settings);

  // Plays the whole source (or until a stop is requested); returns the process's exit code: 0 when at
  // least one frame was published, else 1. Throws std::runtime_error when a --wait-for process stays silent.
  int run();

 private:
  // One line per skipped frame, the first few of a kind, then a summary every few seconds: a folder whose
  // every image has the wrong size must not bury the log. The end's count has them all.
  void warnSkip(const std::string& message);
  void warnSkipsLeftOut();  // the count of skip warnings left out, if any
  // A TUM folder's ground truth for pass `pass` into dataset_truth_out_: all of it for a single pass
  // (evaluation against any subset); with --loop, each pass's own stretch (from half a frame before its
  // first frame to half a frame before the next pass's), offset by the pass's stamp shift. Written as each
  // pass starts: the whole file once per pass made the passes overlap (a frame could be paired with
  // another pass's pose), and --loop 1000000 ran out of memory building it.
  void writeTruthPass(int pass);

  ProcessContext& ctx_;
  CaptureSettings settings_;
  WarningThrottle skip_warnings_;  // before source_: opening it may warn already
  std::unique_ptr<FrameSource> source_;
  bool from_dataset_ = false;
  Trajectory dataset_truth_;  // a TUM folder's ground truth, all of it
  double loop_period_s_ = 0;  // --loop: stamp offset per pass (0: measured by the looped source)
  double pass_first_s_ = 0;   // a TUM pass's first frame's stamp
  double frame_s_ = 0;        // a TUM pass's mean frame interval
  std::optional<TumTrajectoryStream> dataset_truth_out_;
  int64_t truth_written_ = 0;
  int truth_pass_ = 0;  // the pass whose ground truth was written last
};

}  // namespace bmp::capture

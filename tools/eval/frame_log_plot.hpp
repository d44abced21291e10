#pragma once
// The tracker's per-frame log (bmp-tracker --frame-log, frames.tsv) as a picture: inliers over time with
// where each frame's first pose came from and where frames were missed, and the tracking time per frame.
// What a user looks at first when a run went wrong at some moment.
#include <string>
#include <vector>

namespace bmp::eval {

struct FrameLogRow {
  double stamp = 0.0;
  std::string state;        // OK, DEGRADED, LOST, RELOCALISED, ...
  int tracked = 0;          // inliers after the local map
  std::string pose_source;  // motion, reference, relocalisation, map_start, none
  int first_inliers = 0;    // inliers of the first pose
  int frames_missed = 0;    // frames lost or dropped just before this one
  double track_ms = 0.0;
  double position_std_mm = -1.0;  // how well the inliers pin the position; < 0: none ('-', or an older log)
};

// Reads a frame log by its header's column names (the '# stamp<TAB>seq...' line); throws EvalError naming
// the file and line when a line is malformed or a column is missing.
std::vector<FrameLogRow> readFrameLog(const std::string& path);

// Three panels over time: tracked inliers (line), first inliers coloured by pose source, missed frames as
// ticks, lost frames marked; each frame's position std (where the log has it); tracking ms with the 30 Hz
// frame period. Throws EvalError when not written.
void plotFrameLog(const std::string& path, const std::vector<FrameLogRow>& rows, const std::string& title);

}  // namespace bmp::eval

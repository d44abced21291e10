#pragma once
// A per-frame log of what the tracker did (one tab-separated line per frame, flushed as written, so a
// killed process leaves every line): to find out afterwards why a run went wrong at some moment, which a
// trajectory alone does not tell (how many points the first pose kept, whether frames were dropped before
// it, whether the frame had its own boxes).
#include <fstream>
#include <stdexcept>
#include <string>

#include "tracker/tracker.hpp"

namespace bmp::tracker {

class FrameLogError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// What the caller knows about the frame beyond the tracker's result.
struct FrameLogContext {
  int frames_missed = 0;    // frames lost upstream or dropped right before this one
  std::string boxes = "-";  // own: its own detections; stale: an earlier frame's; none; -: no detector
};

class FrameLog {
 public:
  // Creates (truncates) the file and writes the header; throws FrameLogError naming the path.
  explicit FrameLog(const std::string& path);
  void append(const TrackResult& result, const FrameLogContext& context);
  const std::string& path() const { return path_; }

  // The header line's column names, tab-separated (without the leading '#').
  static const char* columns();

 private:
  std::string path_;
  std::ofstream out_;
};

}  // namespace bmp::tracker

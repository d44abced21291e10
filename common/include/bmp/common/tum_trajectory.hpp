#pragma once
// Trajectories in the TUM RGB-D format: "timestamp tx ty tz qx qy qz qw" per line, '#' comments.
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "bmp/common/se3.hpp"
#include "bmp/common/tum_text_list.hpp"  // normalizeTumLine, once declared here

namespace bmp {

struct StampedPose {
  double stamp = 0.0;  // seconds
  SE3 T_world_cam = SE3::Identity();
};
using Trajectory = std::vector<StampedPose>;

class TrajectoryError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Accepts spaces, tabs or commas as separators (as the TUM scripts do). Throws TrajectoryError naming
// file and line for a malformed line; the result is sorted by time.
Trajectory readTumTrajectory(const std::string& path);
Trajectory parseTumTrajectory(const std::string& text, const std::string& origin);
// Replaces the file whole (written beside it, then renamed), so it is never seen half written.
void writeTumTrajectory(const std::string& path, const Trajectory& trajectory);
std::string formatTumLine(const StampedPose& pose);

// A trajectory written pose by pose as it is known, each line flushed: what a killed process leaves behind.
// A non-empty file already at the path (say, a killed run's poses) is kept as <path>.prev, not truncated.
class TumTrajectoryStream {
 public:
  TumTrajectoryStream(const std::string& path, const std::string& comment);
  void append(const StampedPose& pose);
  // Drops every pose written so far (the header stays; the previous file kept at the start is not touched):
  // the poses belonged to a map that was dropped.
  void restart();
  const std::string& path() const { return path_; }
  // Where the file found at the path went ("" when there was none).
  const std::string& previous() const { return previous_; }

 private:
  std::string path_;
  std::string previous_;
  std::string header_;
  std::ofstream out_;
};

}  // namespace bmp

#include "bmp/common/tum_trajectory.hpp"

#include "bmp/common/atomic_file.hpp"
#include "bmp/common/number_format.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

namespace bmp {

namespace {

const TumTextFormat kTrajectoryFormat{"trajectory file", "timestamp tx ty tz qx qy qz qw", 7, true};

Trajectory toTrajectory(const std::vector<TumTextRecord>& records, const std::string& origin) {
  Trajectory out;
  for (const auto& r : records) {
    const Eigen::Quaterniond q(r.number(6), r.number(3), r.number(4), r.number(5));
    if (std::abs(q.norm() - 1.0) > 0.1) {
      throw TrajectoryError(origin + ":" + std::to_string(r.line) +
                            ": not a valid pose (quaternion far from unit length): '" + r.text + "'");
    }
    out.push_back({r.stamp, makeSE3({r.number(0), r.number(1), r.number(2)}, q)});
  }
  std::stable_sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.stamp < b.stamp; });
  return out;
}

}  // namespace

Trajectory parseTumTrajectory(const std::string& text, const std::string& origin) {
  try {
    return toTrajectory(parseTumTextList(text, origin, kTrajectoryFormat), origin);
  } catch (const TumTextError& e) {
    throw TrajectoryError(e.what());
  }
}

Trajectory readTumTrajectory(const std::string& path) {
  try {
    return toTrajectory(readTumTextList(path, kTrajectoryFormat), path);
  } catch (const TumTextError& e) {
    throw TrajectoryError(e.what());
  }
}

std::string formatTumLine(const StampedPose& pose) {
  const Eigen::Vector3d t = pose.T_world_cam.translation();
  const Eigen::Quaterniond q(pose.T_world_cam.linear());
  std::string line = formatFixed(pose.stamp, 6, "nan");
  for (const double v : {t.x(), t.y(), t.z(), q.x(), q.y(), q.z(), q.w()})
    line += " " + formatFixed(v, 7, "nan");
  return line;
}

void writeTumTrajectory(const std::string& path, const Trajectory& trajectory) {
  // Whatever was at the path before, such as a live trajectory, stays until the whole new one is there.
  std::string text = "# timestamp tx ty tz qx qy qz qw\n";
  for (const auto& pose : trajectory) text += formatTumLine(pose) + "\n";
  try {
    writeFileAtomically(path, text);
  } catch (const FileWriteError& e) {
    throw TrajectoryError(e.what());
  }
}

namespace {

std::string keepPrevious(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec) || std::filesystem::file_size(path, ec) == 0) return "";
  const std::string previous = path + ".prev";
  std::filesystem::rename(path, previous, ec);
  if (ec)
    throw TrajectoryError(path + ": cannot keep the previous file as " + previous + ": " + ec.message());
  return previous;
}

}  // namespace

TumTrajectoryStream::TumTrajectoryStream(const std::string& path, const std::string& comment)
    : path_(path),
      previous_(keepPrevious(path)),
      header_((comment.empty() ? "" : "# " + comment + "\n") + "# timestamp tx ty tz qx qy qz qw\n"),
      out_(path) {
  if (!out_) throw TrajectoryError(path + ": cannot write trajectory file");
  out_ << header_ << std::flush;
}

void TumTrajectoryStream::restart() {
  out_.close();
  out_.open(path_, std::ios::trunc);
  if (!out_) throw TrajectoryError(path_ + ": cannot write trajectory file");
  out_ << header_ << std::flush;
}

void TumTrajectoryStream::append(const StampedPose& pose) {
  // Flushed per pose: a process killed at any moment leaves every pose it had published.
  out_ << formatTumLine(pose) << std::endl;
  if (!out_) throw TrajectoryError(path_ + ": write failed");
}

}  // namespace bmp

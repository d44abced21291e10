#include "bmp/common/tum_trajectory.hpp"

#include "bmp/common/atomic_file.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace bmp {

bool normalizeTumLine(std::string& line) {
  std::replace(line.begin(), line.end(), ',', ' ');
  std::replace(line.begin(), line.end(), '\t', ' ');
  if (!line.empty() && line.back() == '\r') line.pop_back();
  const auto first = line.find_first_not_of(' ');
  return first != std::string::npos && line[first] != '#';
}

Trajectory parseTumTrajectory(const std::string& text, const std::string& origin) {
  Trajectory out;
  std::istringstream in(text);
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (!normalizeTumLine(line)) continue;
    std::istringstream fields(line);
    double v[8];
    int n = 0;
    while (n < 8 && fields >> v[n]) ++n;
    std::string extra;
    if (n != 8 || (fields >> extra)) {
      throw TrajectoryError(origin + ":" + std::to_string(line_no) +
                            ": expected 'timestamp tx ty tz qx qy qz qw', got '" + line + "'");
    }
    const Eigen::Quaterniond q(v[7], v[4], v[5], v[6]);
    bool finite = true;
    for (double x : v) finite = finite && std::isfinite(x);
    if (!finite || std::abs(q.norm() - 1.0) > 0.1) {
      throw TrajectoryError(origin + ":" + std::to_string(line_no) +
                            ": not a valid pose (non-finite value or "
                            "quaternion far from unit length): '" +
                            line + "'");
    }
    out.push_back({v[0], makeSE3({v[1], v[2], v[3]}, q)});
  }
  std::stable_sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.stamp < b.stamp; });
  return out;
}

Trajectory readTumTrajectory(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw TrajectoryError(path + ": cannot open trajectory file");
  std::stringstream text;
  text << in.rdbuf();
  return parseTumTrajectory(text.str(), path);
}

std::string formatTumLine(const StampedPose& pose) {
  const Eigen::Vector3d t = pose.T_world_cam.translation();
  const Eigen::Quaterniond q(pose.T_world_cam.linear());
  char buffer[256];
  std::snprintf(buffer, sizeof(buffer), "%.6f %.7f %.7f %.7f %.7f %.7f %.7f %.7f", pose.stamp, t.x(), t.y(),
                t.z(), q.x(), q.y(), q.z(), q.w());
  return buffer;
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
    : path_(path), previous_(keepPrevious(path)), out_(path) {
  if (!out_) throw TrajectoryError(path + ": cannot write trajectory file");
  if (!comment.empty()) out_ << "# " << comment << "\n";
  out_ << "# timestamp tx ty tz qx qy qz qw" << std::endl;
}

void TumTrajectoryStream::append(const StampedPose& pose) {
  // Flushed per pose: a process killed at any moment leaves every pose it had published.
  out_ << formatTumLine(pose) << std::endl;
  if (!out_) throw TrajectoryError(path_ + ": write failed");
}

}  // namespace bmp

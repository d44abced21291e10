#include "eval/eval_input.hpp"

#include "eval/eval_error.hpp"

namespace bmp::eval {

Trajectory uniqueStamps(const Trajectory& sorted) {
  Trajectory out;
  out.reserve(sorted.size());
  for (const auto& pose : sorted) {
    if (!out.empty() && out.back().stamp == pose.stamp) {
      out.back() = pose;  // readTumTrajectory sorts stably, so this is the later line
    } else {
      out.push_back(pose);
    }
  }
  return out;
}

Trajectory loadTrajectory(const std::string& path) {
  Trajectory raw;
  try {
    raw = readTumTrajectory(path);
  } catch (const TrajectoryError& e) {
    throw EvalError(e.what());
  }
  if (raw.empty()) throw EvalError(path + ": no poses in trajectory file");
  return uniqueStamps(raw);
}

}  // namespace bmp::eval

#pragma once
// Human-readable and JSON summaries of one evaluation.
#include <cstddef>
#include <string>

#include "eval/ate.hpp"
#include "eval/body_offset.hpp"
#include "eval/rpe.hpp"

namespace bmp::eval {

struct EvalReport {
  std::string label;
  std::string gt_path;
  std::string est_path;
  std::size_t gt_poses = 0;
  std::size_t est_poses = 0;
  AteOptions ate_options;
  RpeOptions rpe_options;
  AteResult ate;
  RpeResult rpe;
  BodyOffset body_offset;  // between the estimate's camera frame and the ground truth's orientations
};

// Below this share of the estimate's poses paired with ground truth, the text report warns that the ATE
// speaks for part of the run only (ground truth that starts late or stops early, another recording's file).
inline constexpr double kWarnCoverageBelow = 0.9;
// The share of the estimate's poses the ATE paired with ground truth (0 without poses).
double ateCoverage(const EvalReport& report);

std::string formatText(const EvalReport& report);
// One JSON object; NaN statistics (no RPE pairs) become null.
std::string formatJson(const EvalReport& report);
// Throws EvalError naming the path when it cannot be written.
void writeTextFile(const std::string& path, const std::string& text);

}  // namespace bmp::eval

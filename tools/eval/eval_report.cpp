#include "eval/eval_report.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "bmp/common/json_text.hpp"
#include "bmp/common/number_format.hpp"
#include "eval/eval_error.hpp"

namespace bmp::eval {

namespace {

std::string fixed(double v, int digits) {
  return formatFixed(v, digits, "n/a");
}

// Enough digits to round-trip a double.
std::string jsonNumber(double v) {
  if (!std::isfinite(v)) return "null";
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "%.17g", v);
  return buffer;
}

std::string jsonStats(const ErrorStats& s) {
  std::ostringstream out;
  out << "{\"count\": " << s.count << ", \"rmse\": " << jsonNumber(s.rmse)
      << ", \"mean\": " << jsonNumber(s.mean) << ", \"median\": " << jsonNumber(s.median)
      << ", \"std\": " << jsonNumber(s.std) << ", \"min\": " << jsonNumber(s.min)
      << ", \"max\": " << jsonNumber(s.max) << "}";
  return out.str();
}

void statsLines(std::ostringstream& out, const ErrorStats& s, const std::string& unit, int digits,
                double cm_factor) {
  const std::pair<const char*, double> rows[] = {{"rmse", s.rmse}, {"mean", s.mean}, {"median", s.median},
                                                 {"std", s.std},   {"min", s.min},   {"max", s.max}};
  for (const auto& [name, v] : rows) {
    char line[128];
    std::snprintf(line, sizeof(line), "    %-7s %12s %s", name, fixed(v, digits).c_str(), unit.c_str());
    out << line;
    if (cm_factor > 0) out << "  (" << fixed(v * cm_factor, 2) << " cm)";
    out << "\n";
  }
}

}  // namespace

double ateCoverage(const EvalReport& r) {
  return r.est_poses == 0 ? 0.0 : static_cast<double>(r.ate.stats.count) / static_cast<double>(r.est_poses);
}

std::string formatText(const EvalReport& r) {
  std::ostringstream out;
  out << "bmp-eval" << (r.label.empty() ? "" : ": " + r.label) << "\n";
  out << "  ground truth: " << r.gt_path << " (" << r.gt_poses << " poses)\n";
  out << "  estimate:     " << r.est_path << " (" << r.est_poses << " poses)\n";
  out << "ATE (evaluate_ate.py; max diff " << r.ate_options.max_difference << " s, offset "
      << r.ate_options.offset << " s, scale " << r.ate_options.scale << "): " << r.ate.stats.count
      << " pairs\n";
  statsLines(out, r.ate.stats, "m", 6, 100.0);
  if (ateCoverage(r) < kWarnCoverageBelow)
    out << "WARNING: only " << r.ate.stats.count << " of the estimate's " << r.est_poses << " poses ("
        << fixed(100.0 * ateCoverage(r), 1) << " %) have a ground-truth pose within "
        << r.ate_options.max_difference
        << " s: the ATE speaks for that part of the run only. Check that the ground truth is this "
           "recording's and covers it (or widen --max-diff for sparse ground truth).\n";
  if (r.body_offset.constant())
    out << "WARNING: the ground truth's orientations differ from the estimate's camera frame by a constant "
        << fixed(r.body_offset.angle_deg, 1) << " deg (spread " << fixed(r.body_offset.spread_deg, 1)
        << " deg over " << r.body_offset.pairs
        << " pairs): they are not camera orientations (e.g. a motion-capture marker). The ATE (positions) "
           "is unaffected; the RPE below compares motions in different frames and is not meaningful.\n";
  out << "RPE (evaluate_rpe.py --fixed_delta; delta " << r.rpe_options.delta << " "
      << deltaUnitName(r.rpe_options.unit) << "): " << r.rpe.trans.count << " pairs\n";
  if (r.rpe.trans.count == 0) {
    out << "    no pose pairs: trajectories too short for this delta, or too far from ground-truth stamps\n";
    return out.str();
  }
  out << "  translation\n";
  statsLines(out, r.rpe.trans, "m", 6, 100.0);
  out << "  rotation\n";
  statsLines(out, r.rpe.rot_deg, "deg", 6, 0.0);
  return out.str();
}

std::string formatJson(const EvalReport& r) {
  std::ostringstream out;
  out << "{\n";
  out << "  \"label\": " << jsonString(r.label) << ",\n";
  out << "  \"groundtruth\": {\"path\": " << jsonString(r.gt_path) << ", \"poses\": " << r.gt_poses << "},\n";
  out << "  \"estimate\": {\"path\": " << jsonString(r.est_path) << ", \"poses\": " << r.est_poses << "},\n";
  out << "  \"ate\": {\"max_difference_s\": " << jsonNumber(r.ate_options.max_difference)
      << ", \"offset_s\": " << jsonNumber(r.ate_options.offset)
      << ", \"scale\": " << jsonNumber(r.ate_options.scale) << ", \"pairs\": " << r.ate.stats.count
      << ", \"coverage\": " << jsonNumber(ateCoverage(r))
      << ",\n          \"translation_m\": " << jsonStats(r.ate.stats) << "},\n";
  out << "  \"rpe\": {\"delta\": " << jsonNumber(r.rpe_options.delta) << ", \"delta_unit\": \""
      << deltaUnitName(r.rpe_options.unit) << "\", \"offset_s\": " << jsonNumber(r.rpe_options.offset)
      << ", \"scale\": " << jsonNumber(r.rpe_options.scale) << ", \"pairs\": " << r.rpe.trans.count
      << ",\n          \"translation_m\": " << jsonStats(r.rpe.trans)
      << ",\n          \"rotation_deg\": " << jsonStats(r.rpe.rot_deg)
      << ",\n          \"meaningful\": " << (r.body_offset.constant() ? "false" : "true") << "},\n";
  out << "  \"groundtruth_body_offset\": {\"angle_deg\": " << jsonNumber(r.body_offset.angle_deg)
      << ", \"spread_deg\": " << jsonNumber(r.body_offset.spread_deg)
      << ", \"pairs\": " << r.body_offset.pairs
      << ", \"constant\": " << (r.body_offset.constant() ? "true" : "false") << "}\n";
  out << "}\n";
  return out.str();
}

void writeTextFile(const std::string& path, const std::string& text) {
  std::ofstream out(path);
  if (!out) throw EvalError(path + ": cannot open for writing");
  out << text;
  if (!out.flush()) throw EvalError(path + ": write failed");
}

}  // namespace bmp::eval

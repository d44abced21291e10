#include "eval/eval_command.hpp"

#include <cctype>
#include <filesystem>
#include <iostream>
#include <limits>
#include <sstream>

#include "bmp/common/arg_range.hpp"
#include "eval/ate.hpp"
#include "eval/eval_error.hpp"
#include "eval/eval_input.hpp"
#include "eval/eval_plot.hpp"
#include "eval/eval_report.hpp"
#include "eval/frame_log_plot.hpp"
#include "eval/rpe.hpp"

namespace bmp::eval {

ArgParser makeEvalParser() {
  ArgParser args("bmp-eval",
                 "Absolute trajectory error (ATE) and relative pose error (RPE) of an estimated trajectory, "
                 "computed as the TUM RGB-D benchmark's evaluate_ate.py and evaluate_rpe.py --fixed_delta "
                 "do. Both files in TUM format: 'timestamp tx ty tz qx qy qz qw' per line.");
  args.addOption("gt", "FILE", "ground-truth trajectory (required)");
  args.addOption("est", "FILE", "estimated trajectory (required)");
  args.addOption("max-diff", "SECONDS", "largest stamp difference for an ATE association", "0.02");
  args.addOption("offset", "SECONDS", "time offset added to the estimated stamps (ATE and RPE)", "0");
  args.addOption("scale", "FACTOR", "scale applied to the estimated translations (ATE and RPE)", "1");
  args.addOption("rpe-delta", "DELTA", "RPE pose-pair distance, in --rpe-unit", "1.0");
  args.addOption("rpe-unit", "s|f", "unit of --rpe-delta: s (seconds) or f (frames)", "s");
  args.addOption("json", "FILE", "also write the results as JSON");
  args.addOption("plot-dir", "DIR",
                 "write PNG plots there (created if needed): <label>_trajectory.png, <label>_errors.png");
  args.addOption("frame-log", "FILE",
                 "the tracker's per-frame log (bmp-tracker --frame-log); with --plot-dir also "
                 "<label>_frames.png: inliers, first poses' sources, missed frames, position std and "
                 "tracking time over time");
  args.addOption("aligned", "FILE", "write the whole estimate aligned to the ground truth (TUM format)");
  args.addOption("label", "NAME",
                 "name of the run, used in titles and plot file names (default: the --est file name "
                 "without extension)");
  args.addEpilog(
      "\nExample:\n"
      "  bmp-eval --gt ../shared/data/rgbd_bonn_crowd/groundtruth.txt --est out/crowd.txt \\\n"
      "           --label crowd --json out/crowd_eval.json --plot-dir out/plots\n"
      "\nNotes:\n"
      "  RPE keeps every pose pair (the script samples 10000 at random when there are more).\n"
      "  RPE pair error, as in the script: inv(inv(E_j) E_i) * inv(G_j) G_i (E estimate, G ground truth).\n"
      "  Exit status: 0 success, 1 bad command line, 2 bad input (unreadable or malformed file, no "
      "overlap).\n");
  return args;
}

void checkEvalArgs(const ArgParser& args) {
  if (!args.given("gt") || !args.given("est"))
    throw ArgError("bmp-eval: --gt FILE and --est FILE are required (see --help)");
  // A zero or negative delta or scale gives numbers (RPE 0.000 m) that mean nothing.
  numberIn(args, "max-diff", 0.0, std::numeric_limits<double>::infinity());
  numberIn(args, "offset", -std::numeric_limits<double>::max(), std::numeric_limits<double>::max());
  positiveNumber(args, "scale");
  positiveNumber(args, "rpe-delta");
  parseDeltaUnit(args.value("rpe-unit"));
}

namespace {

std::string defaultLabel(const std::string& est_path) {
  const std::string stem = std::filesystem::path(est_path).stem().string();
  return stem.empty() ? "estimate" : stem;
}

// A label may hold spaces or slashes; plot file names get a tame version of it.
std::string fileSafe(const std::string& label) {
  std::string out = label;
  for (char& c : out) {
    const bool keep = std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.';
    if (!keep) c = '_';
  }
  return out;
}

// The report's settings from the command line, then ATE, RPE and the body-offset check of the two files.
EvalReport evaluate(const ArgParser& args, const Trajectory& gt, const Trajectory& est) {
  EvalReport report;
  report.gt_path = args.value("gt");
  report.est_path = args.value("est");
  report.label = args.given("label") ? args.value("label") : defaultLabel(report.est_path);
  if (report.label.empty()) report.label = "estimate";
  report.ate_options.max_difference = args.number("max-diff");
  report.ate_options.offset = args.number("offset");
  report.ate_options.scale = args.number("scale");
  report.rpe_options.delta = args.number("rpe-delta");
  report.rpe_options.unit = parseDeltaUnit(args.value("rpe-unit"));
  report.rpe_options.offset = report.ate_options.offset;
  report.rpe_options.scale = report.ate_options.scale;
  report.gt_poses = gt.size();
  report.est_poses = est.size();
  try {
    report.ate = computeAte(gt, est, report.ate_options);
  } catch (const EvalError& e) {
    throw EvalError(report.est_path + " vs " + report.gt_path + ": " + e.what());
  }
  report.rpe = computeRpe(gt, est, report.rpe_options);
  report.body_offset = measureBodyOffset(gt, est, report.ate, report.ate_options.offset);
  return report;
}

void writePlots(const std::filesystem::path& dir, const EvalReport& report, const Trajectory& gt,
                const Trajectory& aligned) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw EvalError(dir.string() + ": cannot create plot directory: " + ec.message());
  std::ostringstream caption;
  caption << "delta " << report.rpe_options.delta << " " << deltaUnitName(report.rpe_options.unit);
  if (report.body_offset.constant())
    caption << "; NOT MEANINGFUL: ground-truth orientations are not the camera's";
  const std::string stem = fileSafe(report.label);
  const std::string trajectory_png = (dir / (stem + "_trajectory.png")).string();
  const std::string errors_png = (dir / (stem + "_errors.png")).string();
  plotTrajectoryTopView(trajectory_png, gt, aligned, report.ate, report.label);
  plotErrorsOverTime(errors_png, report.ate, report.rpe, gt.front().stamp, caption.str(), report.label);
  std::cout << "plots: " << trajectory_png << ", " << errors_png << "\n";
}

// The frames plot is a picture of the run, not part of the evaluation: a log it cannot read is reported and
// the evaluation stands.
void writeFramePlot(const std::filesystem::path& dir, const std::string& log_path, const std::string& label) {
  const std::string frames_png = (dir / (fileSafe(label) + "_frames.png")).string();
  try {
    plotFrameLog(frames_png, readFrameLog(log_path), label);
    std::cout << "plots: " << frames_png << "\n";
  } catch (const EvalError& e) {
    std::cerr << "bmp-eval: no frames plot: " << e.what() << "\n";
  }
}

}  // namespace

int runEval(const ArgParser& args) {
  const Trajectory gt = loadTrajectory(args.value("gt"));
  const Trajectory est = loadTrajectory(args.value("est"));
  const EvalReport report = evaluate(args, gt, est);
  std::cout << formatText(report) << std::flush;
  if (args.given("json")) writeTextFile(args.value("json"), formatJson(report));
  const Trajectory aligned = alignedTrajectory(est, report.ate.alignment, report.ate_options.scale);
  if (args.given("aligned")) {
    try {
      writeTumTrajectory(args.value("aligned"), aligned);
    } catch (const TrajectoryError& e) {
      throw EvalError(e.what());
    }
  }
  if (args.given("plot-dir")) writePlots(args.value("plot-dir"), report, gt, aligned);
  if (args.given("plot-dir") && args.given("frame-log"))
    writeFramePlot(args.value("plot-dir"), args.value("frame-log"), report.label);
  return 0;
}

}  // namespace bmp::eval

#include "plan_command.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>

#include <opencv2/imgcodecs.hpp>

#include "bmp/common/arg_range.hpp"
#include "bmp/common/atomic_file.hpp"
#include "bmp/common/output_path.hpp"
#include "bmp/common/tool_main.hpp"
#include "plan/live_grid.hpp"
#include "plan/path_output.hpp"

namespace bmp::plan {

namespace {

// Exit statuses, as the README and --help give them (0: a path; 2: bad arguments, from runTool).
constexpr int kNoPath = 1;
constexpr int kNoGrid = 3;
constexpr int kNotWritten = 4;

// Exactly two finite numbers: "0,2,3" is a typo, not the point (0, 2).
Eigen::Vector2d point(const ArgParser& args, const std::string& name) {
  const std::string text = args.value(name);
  const std::size_t comma = text.find(',');
  const std::string parts[2] = {text.substr(0, comma),
                                comma == std::string::npos ? "" : text.substr(comma + 1)};
  double xy[2] = {0, 0};
  for (int i = 0; i < 2; ++i) {
    char* end = nullptr;
    xy[i] = std::strtod(parts[i].c_str(), &end);
    if (parts[i].empty() || *end != '\0' || !std::isfinite(xy[i]))
      throw ArgError("--" + name + " must be X,Y (two numbers, metres), got '" + text + "'");
  }
  return {xy[0], xy[1]};
}

}  // namespace

// --out and --path-out; false, said on stderr, when one could not be written.
bool writeOutputs(const ArgParser& args, const PlanGrid& grid, const PlanResult& path,
                  const PlanOptions& options) {
  try {
    if (args.given("out")) {
      std::vector<uchar> png;
      cv::imencode(".png", drawPath(grid, path, options, 4), png);
      writeFileAtomically(args.value("out"), std::string(png.begin(), png.end()));
    }
    if (args.given("path-out")) writeFileAtomically(args.value("path-out"), pathText(path));
  } catch (const FileWriteError& e) {
    std::fprintf(stderr, "bmp-plan: not written: %s\n", e.what());
    return false;
  }
  return true;
}

int runPlan(const ArgParser& args) {
  // Every argument first, outputs included: a typo must not wait --timeout seconds for a grid to be said.
  if (args.given("map") == args.flag("live")) throw ArgError("give either --map FILE or --live");
  if (!args.given("from") || !args.given("to")) throw ArgError("--from and --to are required");
  const Eigen::Vector2d from = point(args, "from"), to = point(args, "to");
  PlanOptions options;
  options.robot_radius_m = numberIn(args, "robot-radius", 0.0, std::numeric_limits<double>::infinity());
  if (args.value("unknown") != "blocked" && args.value("unknown") != "free")
    throw ArgError("--unknown must be blocked or free");
  options.unknown_is_blocked = args.value("unknown") == "blocked";
  const double timeout_s = args.number("timeout");
  if (!(timeout_s > 0 && timeout_s <= 3600)) throw ArgError("--timeout must be in (0, 3600] seconds");
  checkOutputOption(args, "out");
  checkOutputOption(args, "path-out");
  PlanGrid grid;
  try {
    grid = args.flag("live") ? receiveLiveGrid(args.value("lcm-url"), args.value("channel"), timeout_s)
                             : readMapServerMap(args.value("map"));
  } catch (const MapFileError& e) {
    // Its own exit status: a script can tell "no map to plan on" from "no path on this map".
    std::fprintf(stderr, "bmp-plan: no grid: %s\n", e.what());
    return kNoGrid;
  }
  const PlanResult path = planPath(grid, from, to, options);
  if (path.found)
    std::printf("path length %.3f m, %zu cells\n", path.length_m, path.cells.size());
  else
    std::printf("no path: %s\n", path.reason.c_str());
  std::fflush(stdout);  // the result before any complaint about its files
  if (!writeOutputs(args, grid, path, options)) return kNotWritten;
  return path.found ? 0 : kNoPath;
}

void addPlanOptions(ArgParser& args) {
  args.addOption("map", "FILE", "a map_server YAML (bmp-mapper's occupancy.yaml)");
  args.addFlag("live", "use the next OCCUPANCY_GRID message instead");
  args.addOption("from", "X,Y", "start, metres");
  args.addOption("to", "X,Y", "goal, metres");
  args.addOption("robot-radius", "M", "occupied cells block everything within this distance", "0.2");
  args.addOption("unknown", "blocked|free", "how unknown cells count", "blocked");
  args.addOption("out", "FILE", "PNG of the grid with the path");
  args.addOption("path-out", "FILE", "the path as text, one 'x y' line per cell");
  args.addOption("lcm-url", "URL", "with --live (default: $LCM_DEFAULT_URL, else the project's default)");
  args.addOption("channel", "NAME", "with --live", "OCCUPANCY_GRID");
  args.addOption("timeout", "S", "with --live: how long to wait for a grid (bmp-mapper repeats it every 5 s)",
                 "10");
}

}  // namespace bmp::plan

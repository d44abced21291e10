// bmp-plan: a shortest collision-free path on the mapper's 2-D grid (A*, 8-connected, obstacles grown by the
// robot's radius), from the map_server files (--map) or the live OCCUPANCY_GRID (--live).
#include <cstdio>
#include <sstream>

#include <opencv2/imgcodecs.hpp>

#include "bmp/common/atomic_file.hpp"
#include "bmp/common/tool_main.hpp"
#include "plan/live_grid.hpp"
#include "plan/path_output.hpp"

namespace {

using namespace bmp;

Eigen::Vector2d point(const ArgParser& args, const std::string& name) {
  std::istringstream in(args.value(name));
  double x = 0, y = 0;
  char comma = 0;
  if (!(in >> x >> comma >> y) || comma != ',') throw ArgError("--" + name + " must be X,Y in metres");
  return {x, y};
}

int runPlan(const ArgParser& args) {
  if (args.given("map") == args.flag("live")) throw ArgError("give either --map FILE or --live");
  if (!args.given("from") || !args.given("to")) throw ArgError("--from and --to are required");
  plan::PlanOptions options;
  options.robot_radius_m = args.number("robot-radius");
  if (args.value("unknown") != "blocked" && args.value("unknown") != "free")
    throw ArgError("--unknown must be blocked or free");
  options.unknown_is_blocked = args.value("unknown") == "blocked";
  const double timeout_s = args.number("timeout");
  if (!(timeout_s > 0 && timeout_s <= 3600)) throw ArgError("--timeout must be in (0, 3600] seconds");
  plan::PlanGrid grid;
  try {
    grid = args.flag("live") ? plan::receiveLiveGrid(args.value("lcm-url"), args.value("channel"), timeout_s)
                             : plan::readMapServerMap(args.value("map"));
  } catch (const plan::MapFileError& e) {
    // Its own exit status: a script can tell "no map to plan on" from "no path on this map" (1).
    std::fprintf(stderr, "bmp-plan: no grid: %s\n", e.what());
    return 3;
  }
  const plan::PlanResult path = plan::planPath(grid, point(args, "from"), point(args, "to"), options);
  if (args.given("out")) {
    std::vector<uchar> png;
    cv::imencode(".png", plan::drawPath(grid, path, options, 4), png);
    writeFileAtomically(args.value("out"), std::string(png.begin(), png.end()));
  }
  if (args.given("path-out")) writeFileAtomically(args.value("path-out"), plan::pathText(path));
  if (!path.found) {
    std::printf("no path: %s\n", path.reason.c_str());
    return 1;
  }
  std::printf("path length %.3f m, %zu cells\n", path.length_m, path.cells.size());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  bmp::ArgParser args(
      "bmp-plan",
      "Plans a shortest collision-free path (A*, 8-connected) on bmp-mapper's occupancy grid. "
      "Coordinates are metres in the grid's floor plane. Exit 0 with a path, 1 without, 2 on bad arguments, "
      "3 when no grid could be read (file, or no message within --timeout).");
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
  return bmp::runTool(args, argc, argv, runPlan);
}

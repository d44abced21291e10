// bmp-plan: a shortest collision-free path on the mapper's 2-D grid (A*, 8-connected, obstacles grown by the
// robot's radius), from the map_server files (--map) or the live OCCUPANCY_GRID (--live).
#include "bmp/common/tool_main.hpp"
#include "plan_command.hpp"

int main(int argc, char** argv) {
  bmp::ArgParser args(
      "bmp-plan",
      "Plans a shortest collision-free path (A*, 8-connected) on bmp-mapper's occupancy grid. "
      "Coordinates are metres in the grid's floor plane. Exit 0 with a path, 1 without, 2 on bad arguments, "
      "3 when no grid could be read (file, or no message within --timeout), 4 when --out or --path-out "
      "could not be written.");
  bmp::plan::addPlanOptions(args);
  return bmp::runTool(args, argc, argv, bmp::plan::runPlan);
}

// bmp-mapper: SLAM_KEYFRAME and SLAM_KEYFRAME_POSES in; OCTOMAP, OCCUPANCY_GRID and MAP_CLOUD out; map files
// on exit, on SIGUSR1 and at an interval. The algorithm is bmp::mapper::Mapper, its LCM side MapperNode.
#include "bmp/lcm/process.hpp"
#include "mapper/lcm/mapper_node.hpp"
#include "mapper/map_files.hpp"
#include "mapper/mapper_config.hpp"

namespace {

using namespace bmp;

void addOptions(ArgParser& args) {
  args.addOption("out", "DIR", "folder for the map files (created if missing)", "map");
  args.addEpilog(
      "Writes DIR/map.pcd, map.ply, map.bt, occupancy.yaml + occupancy.N.pgm (ROS map_server; the YAML\n"
      "names the save's numbered image), occupancy.pgm (the latest image), cloud_top.png,\n"
      "cloud_oblique.png and occupancy.png on exit (SIGINT/SIGTERM), on SIGUSR1 and every\n"
      "process.save_period_s seconds. A run that maps no keyframe leaves a map already in DIR as it\n"
      "was. Example:\n"
      "  bmp-mapper --out out/latest/map &  kill -USR1 $!   # save now\n");
}

int run(ProcessContext& ctx) {
  const mapper::MapperSettings settings = mapper::mapperSettingsFromConfig(ctx.config.section("mapper"));
  const mapper::MapperProcessSettings process =
      mapper::processSettingsFromConfig(ctx.config.section("process"));
  finishConfig(ctx);
  // A folder that cannot be written is found now, not after the whole run when the map would be lost.
  mapper::checkMapFolder(ctx.args.value("out"));
  mapper::MapperNode node(ctx, settings, process, ctx.args.value("out"));
  ctx.status.tick(true);
  node.run();
  // Every exit but a kill: what was mapped is on disk, or the exit status says it is not.
  const bool saved = node.saveAtExit();
  ctx.status.finish();
  return saved ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  return bmp::runProcess(argc, argv,
                         {"bmp-mapper",
                          "The dense static map: subscribes SLAM_KEYFRAME and SLAM_KEYFRAME_POSES, publishes "
                          "OCTOMAP, OCCUPANCY_GRID and MAP_CLOUD, and writes the map files.",
                          "mapper.yaml", addOptions, run});
}

// tum2lcm: writes a TUM-format folder as an LCM log of RGBD_FRAME messages, for lcm-logplayer. The work is
// convertTumToLcmLog (tum_to_lcm_log.hpp); this file declares the options.
#include "bmp/common/arg_parser.hpp"
#include "bmp/common/tool_main.hpp"
#include "bmp/lcm/channels.hpp"
#include "tum_to_lcm_log.hpp"

int main(int argc, char** argv) {
  bmp::ArgParser args("tum2lcm",
                      "Writes a TUM-format RGB-D folder as an LCM log of RGBD_FRAME messages (the files' "
                      "bytes, not re-encoded), stamped with the recorded times, for lcm-logplayer.");
  args.addOption("dataset", "DIR", "TUM-format folder");
  args.addOption("out", "FILE", "LCM log to write (refused if it exists, unless --force)");
  args.addFlag("force", "replace an existing --out (as lcm-logger's --force)");
  args.addOption("camera", "FILE", "camera YAML; default: DIR/camera.yaml, else chosen by the folder name");
  args.addOption("channel", "NAME", "channel of the frames", bmp::channels::kFrames);
  args.addOption("start", "N", "first associated frame", "0");
  args.addOption("end", "N", "one past the last frame; -1 = all", "-1");
  args.addOption("every", "K", "every K-th frame", "1");
  args.addOption("verify", "HOW", "header | decode", "header");
  args.addOption("max-diff", "S", "colour/depth association window, seconds", "0.02");
  args.addEpilog(
      "Example:\n  tum2lcm --dataset ../shared/data/rgbd_bonn_crowd --out bonn.lcmlog\n"
      "  lcm-logplayer bonn.lcmlog      # replays RGBD_FRAME into running processes\n");
  return bmp::runTool(args, argc, argv, bmp::capture::convertTumToLcmLog);
}

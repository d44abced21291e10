// bmp-run: starts the processes of a run, plays a sequence, stops them cleanly, gathers their outputs into
// out/<run>/ and evaluates the trajectory against the ground truth. The work is runSession
// (run_session.hpp); this file declares the options.
#include "bmp/common/arg_parser.hpp"
#include "bmp/common/tool_main.hpp"
#include "bmp/lcm/process.hpp"
#include "launcher/run_session.hpp"

int main(int argc, char** argv) {
  bmp::ArgParser args(
      "bmp-run",
      "Runs the BMP-SLAM pipeline: starts the processes listed in the run configuration, plays the "
      "synthetic scene or a TUM-format folder through bmp-capture, stops everything cleanly when the "
      "sequence ends, and evaluates the trajectory against the ground truth (ATE, RPE, plots).");
  args.addOption("dataset", "DIR", "TUM-format folder; without it the built-in synthetic scene plays");
  args.addOption("camera", "FILE", "camera YAML for the dataset (default: chosen by bmp-capture)");
  args.addOption("config", "FILE", "run configuration", bmp::configDir() + "/run.yaml");
  args.addOption("out", "DIR",
                 "run folder (default: <output_root>/<time>_<sequence>, linked as latest); an earlier run "
                 "there moves into DIR/previous/");
  args.addOption("mode", "MODE", "capture mode: lockstep | realtime | fast (default: run.mode)");
  args.addOption("speed", "X", "realtime mode: recorded rate x X");
  args.addOption("frames", "N", "play only the first N frames");
  args.addOption("loop", "N", "play the sequence N times as one stream (bmp-capture --loop; soak runs)");
  args.addOption("lcm-url", "URL", "LCM URL for every process; else $LCM_DEFAULT_URL, else the default");
  args.addFlag("no-eval", "do not evaluate");
  args.addEpilog(
      "Outputs in the run folder: trajectory.txt (TUM), groundtruth.txt, eval.json, plots/*.png,\n"
      "logs/<process>.log. Exit status: 0 success, 1 a process or the evaluation failed, 2 a bad option\n"
      "(nothing started), 130 stopped by Ctrl-C (143 by SIGTERM).\n");
  return bmp::runTool(args, argc, argv, bmp::launcher::runSession);
}

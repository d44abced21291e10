// bmp-bench-detector: median and p95 of the detector's per-frame time for each model and input size. The
// work is runDetectorBenchmark (detector_bench.hpp); this file declares the options.
#include "bmp/common/arg_parser.hpp"
#include "bmp/common/config_dir.hpp"
#include "bmp/common/tool_main.hpp"
#include "detector/shared_paths.hpp"
#include "detector_bench.hpp"

int main(int argc, char** argv) {
  bmp::ArgParser args("bmp-bench-detector",
                      "Times the detector per frame (decode + letterbox + inference + NMS) for each model on "
                      "real frames, and prints median, p95 and the ratio of the median to the 30 ms target. "
                      "Run it on an otherwise idle machine, from a Release build.");
  args.addOption("input", "PATH", "TUM sequence folder, image folder or image",
                 bmp::detector::resolveSharedPath("data/rgbd_bonn_crowd"));
  args.addOption("frames", "N", "frames to time per model, spread over the input", "100");
  args.addOption("warmup", "N", "untimed frames first", "5");
  args.addOption("models", "LIST", "comma-separated: yolov5n-320, yolov5n-640, yolo-fastest-xl",
                 "yolov5n-320,yolov5n-640,yolo-fastest-xl");
  args.addOption("threads", "N", "OpenCV threads instead of the configured number");
  args.addOption("config", "FILE", "detector configuration (thresholds, threads)",
                 bmp::configDir() + "/detector.yaml");
  return bmp::runTool(args, argc, argv, bmp::detect_tools::runDetectorBenchmark);
}

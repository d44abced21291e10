// bmp-detect: run the detector on an image, a folder or a TUM sequence and write what it sees. The work is
// runDetect (detect_run.hpp); this file declares the options.
#include "bmp/common/arg_parser.hpp"
#include "bmp/common/config_dir.hpp"
#include "bmp/common/tool_main.hpp"
#include "detect_run.hpp"

int main(int argc, char** argv) {
  bmp::ArgParser args(
      "bmp-detect",
      "Runs the detector on one image, every PNG/JPEG of a folder, or the colour frames of a "
      "TUM sequence folder (rgb.txt), prints the boxes and, with --out, writes annotated PNGs "
      "(high-dynamic red, medium orange, low green) and JSON.");
  args.addOption("input", "PATH", "image file, image folder, or TUM sequence folder");
  args.addOption("out", "DIR", "write <name>.png (annotated) and <name>.json per image here");
  args.addFlag("jsonl", "with --out: one detections.jsonl instead of a JSON file per image");
  args.addOption("config", "FILE", "detector configuration", bmp::configDir() + "/detector.yaml");
  args.addOption("dynamic-classes", "FILE", "dynamic levels; default: dynamic_classes of the configuration");
  args.addOption("model", "NAME",
                 "yolov5n-320, yolov5n-640 or yolo-fastest-xl instead of the configured model");
  args.addOption("conf", "X", "confidence threshold instead of the configured one");
  args.addOption("threads", "N", "OpenCV threads instead of the configured number");
  args.addOption("limit", "N", "stop after N images");
  return bmp::runTool(args, argc, argv, bmp::detect_tools::runDetect);
}

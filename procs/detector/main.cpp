// bmp-detector: YOLO boxes, each tagged with its dynamic level, for every RGB-D frame it processes. The
// algorithm is detector::Detector, its LCM side DetectorNode (lcm/); this file reads settings, runs the node.
#include <sys/resource.h>

#include <cerrno>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <string>

#include "bmp/common/log.hpp"
#include "bmp/lcm/process.hpp"
#include "detector/detector_settings.hpp"
#include "detector/lcm/detector_node.hpp"

namespace {

using namespace bmp;
using namespace bmp::detector;

// Real time: the detector yields the CPU to the tracker (settings.latest_nice). Set before the node starts
// its threads, which inherit it; never raises the priority of a process started nicer.
void yieldInRealTime(const DetectorSettings& settings) {
  if (settings.mode != QueueMode::kLatest || settings.latest_nice <= 0) return;
  errno = 0;
  const int current = getpriority(PRIO_PROCESS, 0);
  if (errno == 0 && current >= settings.latest_nice) return;
  if (setpriority(PRIO_PROCESS, 0, settings.latest_nice) != 0)
    log::warn("could not set nice ", settings.latest_nice, ": ", std::strerror(errno));
  else
    log::info("nice ", settings.latest_nice, " (mode latest: the tracker's poses come first)");
}

int run(ProcessContext& ctx) {
  const auto mode =
      ctx.args.given("mode") ? std::optional<std::string>(ctx.args.value("mode")) : std::nullopt;
  DetectorSettings settings = detectorSettingsFromConfig(ctx.config, mode, configDir());
  finishConfig(ctx);  // unknown keys are refused before the model loads
  if (ctx.args.given("model")) {
    try {
      settings.detector = withModelPreset(settings.detector, ctx.args.value("model"));
    } catch (const std::invalid_argument& e) {
      throw ArgError(std::string("--model: ") + e.what());
    }
    log::info("--model ", ctx.args.value("model"), ": ", settings.detector.model_path, ", input ",
              settings.detector.input_size, " px (instead of the configuration's model)");
  }
  yieldInRealTime(settings);
  DetectorNode node(ctx, settings);
  ctx.status.tick(true);  // the first heartbeat also tells others we are subscribed
  return node.run();
}

}  // namespace

int main(int argc, char** argv) {
  return bmp::runProcess(
      argc, argv,
      {"bmp-detector",
       "Runs YOLO (OpenCV DNN) on the colour image of each RGB-D frame and publishes the boxes, each with "
       "its class, score and dynamic level (high / medium / low, config/dynamic_classes.yaml). In mode "
       "'latest' a frame arriving while the detector is busy replaces the waiting one (drops are counted in "
       "PROCESS_STATUS); in mode 'every' every frame is processed, for lockstep runs.",
       "detector.yaml",
       [](ArgParser& args) {
         args.addOption("mode", "latest|every", "override process.mode of the configuration");
         args.addOption(
             "model", "NAME",
             "a model in the shared folder instead of the configuration's: yolov5n-320, yolov5n-640 "
             "(the paper's input size; about 3 times the time), yolo-fastest-xl");
       },
       run});
}

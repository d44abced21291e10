// bmp-capture: plays a TUM-format folder, or the synthetic scene, as RGBD_FRAME messages. The frame sources
// are in the bmp_capture library, the settings in capture_settings, the LCM side in CaptureNode (lcm/); this
// file reads the settings and runs the node.
#include "bmp/lcm/process.hpp"
#include "capture/capture_settings.hpp"
#include "capture/lcm/capture_node.hpp"

namespace {

using namespace bmp;
using namespace bmp::capture;

int run(ProcessContext& ctx) {
  CaptureSettings settings = readCaptureSettings(ctx.config.section("capture"), ctx.args, configDir());
  finishConfig(ctx);
  CaptureNode node(ctx, std::move(settings));
  return node.run();
}

}  // namespace

int main(int argc, char** argv) {
  return bmp::runProcess(
      argc, argv,
      {"bmp-capture",
       "Plays a TUM-format RGB-D folder, or the built-in synthetic scene, as RGBD_FRAME "
       "messages over LCM, in real time, as fast as possible, or in lockstep with the tracker.",
       "capture.yaml", addCaptureOptions, run});
}

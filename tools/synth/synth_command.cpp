#include "synth_command.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "bmp/common/arg_range.hpp"
#include "bmp/common/config.hpp"
#include "bmp/common/log.hpp"
#include "bmp/common/timing.hpp"
#include "capture/synthetic_config.hpp"
#include "capture/tum_folder_writer.hpp"

namespace bmp::synth {

namespace {

constexpr long long kMaxFrames = 1000000;  // over 9 hours at 30 Hz

constexpr const char* kDefaultConfig = "config/synthetic.yaml";

// Rendering time alone (no PNG encoding or disk), for the 20 ms per frame budget.
int benchmark(const capture::SyntheticScene& scene, int frames) {
  constexpr double kBudgetMs = 20.0;
  TimingStats stats;
  for (int i = 0; i < frames; ++i) {
    Stopwatch watch;
    scene.render(i % scene.numFrames());
    stats.add(watch.elapsedMs());
  }
  std::printf(
      "render %dx%d: median %.2f ms, p95 %.2f ms over %d frames (median x%.2f of the %.0f ms budget)\n",
      scene.camera().width, scene.camera().height, stats.median(), stats.p95(), frames,
      stats.median() / kBudgetMs, kBudgetMs);
  return 0;
}

// The file's "synthetic" section (the built-in defaults when the default file is absent), then the options.
capture::SyntheticSceneConfig sceneConfig(const ArgParser& args) {
  capture::SyntheticSceneConfig config;
  const std::string config_path = args.value("config");
  if (args.given("config") || std::filesystem::exists(config_path)) {
    const Config file = Config::fromFile(config_path);
    config = capture::syntheticSceneFromConfig(file.section("synthetic"));
    file.finish();
  } else {
    log::warn("no ", config_path, " here: using the built-in defaults");
  }
  if (args.given("frames")) config.num_frames = static_cast<int>(integerIn(args, "frames", 1, kMaxFrames));
  if (args.given("seed")) config.seed = args.integer("seed");
  if (args.flag("static")) config.num_moving_objects = 0;
  return config;
}

}  // namespace

void addSynthOptions(ArgParser& args) {
  args.addOption("config", "FILE", "YAML file with a 'synthetic:' section", kDefaultConfig);
  args.addOption("out", "DIR", "output folder: created, or an empty one (see --overwrite)", "synthetic");
  args.addFlag("overwrite",
               "replace a sequence bmp-synth wrote in --out before (its lists, images and camera.yaml); a "
               "folder holding anything else is still refused");
  args.addOption("frames", "N", "number of frames (overrides the configuration)");
  args.addOption("seed", "N", "random seed for textures and motion (overrides the configuration)");
  args.addFlag("static", "no moving objects (num_moving_objects = 0)");
  args.addOption("bench", "N",
                 "benchmark: render N frames without writing and print median/p95 ms per frame");
  args.addEpilog(
      "\nWrites DIR/rgb/*.png, DIR/depth/*.png (16 bit), DIR/mask/*.png (255 on moving objects),\n"
      "DIR/rgb.txt, DIR/depth.txt, DIR/groundtruth.txt and DIR/camera.yaml.\n"
      "A folder that is not empty is refused (exit 1), so a typo cannot overwrite a recorded sequence.\n"
      "Example: bmp-synth --out /tmp/synth_static --static --frames 300\n");
}

int runSynth(const ArgParser& args) {
  const capture::SyntheticSceneConfig config = sceneConfig(args);
  const std::string out = args.value("out");
  // Before the scene is built (seconds with people): a refused folder or count is said at once.
  const int bench_frames =
      args.given("bench") ? static_cast<int>(integerIn(args, "bench", 1, kMaxFrames)) : 0;
  if (!args.given("bench")) capture::prepareTumFolder(out, args.flag("overwrite"));
  Stopwatch setup;
  const capture::SyntheticScene scene(config);
  if (args.given("bench")) return benchmark(scene, bench_frames);
  log::info("scene ready in ", static_cast<int>(setup.elapsedMs()), " ms: ", config.num_frames,
            " frames, seed ", config.seed, ", ", scene.movingObjects(0).size(), " moving objects -> ", out);
  Stopwatch total;
  capture::writeTumFolder(scene, out, [&](int done, int count) {
    if (done % 30 == 0 || done == count)
      std::fprintf(stderr, "\r%d / %d frames (%.1f ms per frame incl. PNG)", done, count,
                   total.elapsedMs() / done);
    if (done == count) std::fprintf(stderr, "\n");
  });
  log::info("wrote ", out, " in ", std::lround(total.elapsedMs() / 1000.0), " s");
  return 0;
}

}  // namespace bmp::synth

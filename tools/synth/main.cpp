// bmp-synth: renders the synthetic scene (textured room, moving objects, exact poses and masks) into a
// TUM-format folder that bmp-capture and the evaluation tools read like any recorded sequence.
#include <cstdio>
#include <exception>
#include <filesystem>
#include <iostream>

#include "bmp/common/arg_parser.hpp"
#include "bmp/common/config.hpp"
#include "bmp/common/log.hpp"
#include "bmp/common/timing.hpp"
#include "capture/synthetic_config.hpp"
#include "capture/tum_folder_writer.hpp"

namespace {

constexpr const char* kDefaultConfig = "config/synthetic.yaml";

// Rendering time alone (no PNG encoding or disk), for the 20 ms per frame budget.
int benchmark(const bmp::capture::SyntheticScene& scene, int frames) {
  constexpr double kBudgetMs = 20.0;
  bmp::TimingStats stats;
  for (int i = 0; i < frames; ++i) {
    bmp::Stopwatch watch;
    scene.render(i % scene.numFrames());
    stats.add(watch.elapsedMs());
  }
  std::printf(
      "render %dx%d: median %.2f ms, p95 %.2f ms over %d frames (median x%.2f of the %.0f ms budget)\n",
      scene.camera().width, scene.camera().height, stats.median(), stats.p95(), frames,
      stats.median() / kBudgetMs, kBudgetMs);
  return 0;
}

int run(int argc, const char* const* argv) {
  bmp::ArgParser args("bmp-synth", "Render the synthetic RGB-D scene into a TUM-format folder.");
  args.addOption("config", "FILE", "YAML file with a 'synthetic:' section", kDefaultConfig);
  args.addOption("out", "DIR", "output folder (created)", "synthetic");
  args.addOption("frames", "N", "number of frames (overrides the configuration)");
  args.addOption("seed", "N", "random seed for textures and motion (overrides the configuration)");
  args.addFlag("static", "no moving objects (num_moving_objects = 0)");
  args.addOption("bench", "N",
                 "benchmark: render N frames without writing and print median/p95 ms per frame");
  args.addEpilog(
      "\nWrites DIR/rgb/*.png, DIR/depth/*.png (16 bit), DIR/mask/*.png (255 on moving objects),\n"
      "DIR/rgb.txt, DIR/depth.txt and DIR/groundtruth.txt.\n"
      "Example: bmp-synth --out /tmp/synth_static --static --frames 300\n");
  if (!args.parse(argc, argv)) {
    std::cout << args.help();
    return 0;
  }

  bmp::capture::SyntheticSceneConfig config;
  const std::string config_path = args.value("config");
  if (args.given("config") || std::filesystem::exists(config_path)) {
    const bmp::Config file = bmp::Config::fromFile(config_path);
    config = bmp::capture::syntheticSceneFromConfig(file.section("synthetic"));
    file.finish();
  } else {
    bmp::log::warn("no ", config_path, " here: using the built-in defaults");
  }
  if (args.given("frames")) config.num_frames = static_cast<int>(args.integer("frames"));
  if (args.given("seed")) config.seed = args.integer("seed");
  if (args.flag("static")) config.num_moving_objects = 0;

  const std::string out = args.value("out");
  bmp::Stopwatch setup;
  const bmp::capture::SyntheticScene scene(config);
  if (args.given("bench")) return benchmark(scene, static_cast<int>(args.integer("bench")));
  bmp::log::info("scene ready in ", static_cast<int>(setup.elapsedMs()), " ms: ", config.num_frames,
                 " frames, seed ", config.seed, ", ", config.num_moving_objects, " moving objects -> ", out);
  bmp::Stopwatch total;
  bmp::capture::writeTumFolder(scene, out, [&](int done, int count) {
    if (done % 30 == 0 || done == count)
      std::fprintf(stderr, "\r%d / %d frames (%.1f ms per frame incl. PNG)", done, count,
                   total.elapsedMs() / done);
    if (done == count) std::fprintf(stderr, "\n");
  });
  bmp::log::info("wrote ", out, " in ", static_cast<int>(total.elapsedMs() / 1000.0 + 0.5), " s");
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const bmp::ArgError& e) {
    std::cerr << "bmp-synth: " << e.what() << "\n(see --help)\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "bmp-synth: " << e.what() << "\n";
    return 1;
  }
}

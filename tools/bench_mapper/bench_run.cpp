#include "bench_run.hpp"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>
#include <stdexcept>
#include <thread>

#include "bmp/common/arg_range.hpp"
#include "bmp/common/config.hpp"
#include "bmp/common/image_codec.hpp"
#include "bmp/common/memory_usage.hpp"
#include "bmp/common/timing.hpp"
#include "bmp/common/tool_main.hpp"
#include "bmp/common/tum_trajectory.hpp"
#include "bmp/lcm/process.hpp"
#include "capture/camera_selection.hpp"
#include "capture/synthetic_scene.hpp"
#include "capture/tum_sequence.hpp"
#include "capture/tum_source.hpp"
#include "mapper/map_files.hpp"
#include "mapper/mapper_config.hpp"

namespace bmp::mapper {

namespace {

constexpr long long kMaxCount = 1000000;  // keyframes, loops, frame step: beyond any real sequence

// The ground-truth pose nearest in time (within 0.02 s), or false.
bool poseAt(const Trajectory& gt, double stamp, SE3& T) {
  double best = 0.02;
  bool found = false;
  for (const auto& p : gt) {
    if (std::abs(p.stamp - stamp) <= best) {
      best = std::abs(p.stamp - stamp);
      T = p.T_world_cam;
      found = true;
    }
  }
  return found;
}

// A Bonn RGB-D Dynamic folder, by the folder's or the camera file's name (as the camera is chosen).
bool bonnSequence(const std::string& dir, const std::string& camera_file) {
  namespace fs = std::filesystem;
  fs::path folder = fs::absolute(dir).lexically_normal();
  if (folder.filename().empty()) folder = folder.parent_path();  // "dir/"
  std::string name = folder.filename().string() + " " + fs::path(camera_file).stem().string();
  std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return std::tolower(c); });
  return name.find("bonn") != std::string::npos;
}

// The poses the keyframes are placed at: --poses, else the folder's ground truth. Bonn's ground truth is the
// motion-capture marker body, about 176 degrees off the camera (README, "Reading the evaluation"): mapped
// as camera poses each keyframe's cloud is turned about the marker and the map smears, so it is said.
Trajectory keyframePoses(const ArgParser& args, const capture::SequenceIndex& index,
                         const std::string& camera_file, bool warn) {
  const std::string dir = args.value("dataset");
  if (args.given("poses")) {
    Trajectory poses = readTumTrajectory(args.value("poses"));
    if (poses.empty()) throw std::runtime_error(args.value("poses") + ": no poses");
    return poses;
  }
  if (index.groundtruth.empty())
    throw std::runtime_error(dir + ": no groundtruth.txt (give camera poses with --poses FILE)");
  if (warn && bonnSequence(dir, camera_file))
    std::fprintf(stderr,
                 "warning: %s: Bonn RGB-D Dynamic's groundtruth.txt is the pose of the motion-capture marker "
                 "body, about 176 degrees off the camera, so a map built on it is smeared (the timing still "
                 "holds); give --poses FILE with camera poses (a run's trajectory.txt, or bmp-bench-tracker "
                 "--trajectory FILE) for a map to look at\n",
                 dir.c_str());
  return index.groundtruth;
}

// One pass over the sequence; loop numbers the pass, so a replayed frame gets a new keyframe id.
// first: the first keyframe mapped (kept, as nothing came before it to merge into), for the rebuild timing.
void feedTum(const ArgParser& args, int every, int limit, int loop, Mapper& m,
             std::optional<PoseUpdate>& first) {
  capture::SequenceIndex index = capture::indexSequence(args.value("dataset"));
  const int64_t frames = static_cast<int64_t>(index.frames.size());
  const capture::SequenceCamera selected =
      capture::selectCamera(args.value("dataset"), args.value("camera"), configDir() + "/cameras");
  const CameraIntrinsics& camera = selected.intrinsics;
  const Trajectory poses = keyframePoses(args, index, selected.file, loop == 0);
  // bmp-capture's reader: a missing, corrupt or wrongly sized file is skipped and named, as in the pipeline.
  capture::TumSourceOptions options;
  options.selection.every = every;
  if (loop == 0)
    options.warn = [](const std::string& line) { std::fprintf(stderr, "warning: %s\n", line.c_str()); };
  capture::TumSource source(std::move(index), camera, std::move(options));
  int fed = 0;
  while (fed < limit) {
    const auto frame = source.next();
    if (!frame) break;
    KeyframeInput kf;
    kf.id = static_cast<int64_t>(loop) * frames + frame->index;
    kf.camera = camera;
    if (!poseAt(poses, frame->stamp, kf.T_world_cam)) continue;
    try {
      kf.color = decodeImage(frame->color);
      kf.depth = decodeImage(frame->depth);
    } catch (const ImageError& e) {
      std::fprintf(stderr, "frame %lld: %s\n", static_cast<long long>(frame->index), e.what());
      continue;
    }
    const IntegrateResult r = m.integrate(kf);
    if (!r.ok)
      std::fprintf(stderr, "frame %lld: %s\n", static_cast<long long>(frame->index), r.reason.c_str());
    if (r.ok && !first) first = PoseUpdate{kf.id, kf.T_world_cam};
    fed += r.ok;
  }
  if (fed == 0 && limit > 0)
    throw std::runtime_error(args.value("dataset") + ": no frame with a pose (" +
                             (args.given("poses") ? args.value("poses") : std::string("groundtruth.txt")) +
                             ") could be read and integrated (each skip is named above)");
}

void feedSynthetic(int every, int limit, int loop, Mapper& m, std::optional<PoseUpdate>& first) {
  const capture::SyntheticScene scene{capture::SyntheticSceneConfig{}};
  int fed = 0;
  for (int i = 0; i < scene.numFrames() && fed < limit; i += every, ++fed) {
    const capture::SyntheticFrame f = scene.render(i);
    const int64_t id = static_cast<int64_t>(loop) * scene.numFrames() + i;
    KeyframeInput kf{id, f.stamp, f.T_world_cam, scene.camera(), f.bgr, f.depth, f.mask};
    if (m.integrate(kf).ok && !first) first = PoseUpdate{kf.id, kf.T_world_cam};
  }
}

}  // namespace

int runBenchMapper(const ArgParser& args) {
  const Config file = Config::fromFile(args.value("config"));
  MapperSettings settings = mapperSettingsFromConfig(file.section("mapper"));
  file.ignore("process");
  file.finish();
  if (args.given("pixel-step"))
    settings.cloud.pixel_step =
        static_cast<int>(integerIn(args, "pixel-step", 1, CloudSettings::kMaxPixelStep));
  if (args.flag("synthetic")) {  // the synthetic world: z up, floor at 0
    settings.grid.up = {0, 0, 1};
    settings.grid.height_max_m = 1.9;
  }
  const int every = static_cast<int>(integerIn(args, "every", 1, kMaxCount));
  const int limit =
      args.given("keyframes") ? static_cast<int>(integerIn(args, "keyframes", 1, kMaxCount)) : 1 << 30;
  const int loops = static_cast<int>(integerIn(args, "loops", 1, kMaxCount));
  if (!args.flag("synthetic") && !args.given("dataset")) throw ArgError("give --dataset DIR or --synthetic");
  if (args.given("poses") && !args.given("dataset")) throw ArgError("--poses needs --dataset DIR");
  Mapper m(settings);
  std::optional<PoseUpdate> first;
  // Each pass maps the same room again: with bounded memory the peak levels off after the first.
  for (int loop = 0; loop < loops; ++loop) {
    if (args.flag("synthetic"))
      feedSynthetic(every, limit, loop, m, first);
    else
      feedTum(args, every, limit, loop, m, first);
    if (loops > 1)
      std::printf("loop %d          keyframes kept %zu, merged %zu, peak resident %.0f MiB\n", loop + 1,
                  m.keyframeCount(), m.mergedCount(),
                  static_cast<double>(bmp::peakResidentBytes()) / (1 << 20));
  }
  const TimingStats& t = m.integrationTimes();
  std::printf("keyframes        %zu\n", t.count());
  std::printf("integrate ms     median %.1f, p95 %.1f, max %.1f\n", t.median(), t.p95(), t.max());
  std::printf("cloud points     %zu\n", m.cloud().size());
  if (const auto& floor = m.floor())
    std::printf("floor            normal (%.3f %.3f %.3f), %.3f m along it, %.0f %% of the points\n",
                floor->normal.x(), floor->normal.y(), floor->normal.z(), floor->height, 100 * floor->share);
  else
    std::printf("floor            none fitted (grid.floor)\n");
  std::printf("octree nodes     %zu (%.1f MiB)\n", m.occupancy().nodeCount(),
              static_cast<double>(m.occupancy().memoryBytes()) / (1 << 20));
  std::printf("peak resident    %.0f MiB\n", static_cast<double>(bmp::peakResidentBytes()) / (1 << 20));
  if (args.given("out"))
    std::printf("files            %zu in %s\n", writeMapFiles(args.value("out"), m).size(),
                args.value("out").c_str());
  // What a pose update costs the mapper (after the files: it moves a keyframe): every kept keyframe and its
  // kept revisits cast again, on a thread of their own; the mapper's loop only starts it and swaps it in.
  if (first) {
    first->T_world_cam.translation() += Eigen::Vector3d(0.03, 0.0, 0.0);
    m.updatePoses({*first});
    const Stopwatch watch;
    double longest_turn_ms = 0;
    for (bool swapped = false; !swapped;) {
      const Stopwatch turn;
      swapped = m.maintain(0.0);
      longest_turn_ms = std::max(longest_turn_ms, turn.elapsedMs());
      if (!swapped) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    const double rebuild_ms = watch.elapsedMs();
    const Stopwatch carve;
    m.cloud();
    std::printf(
        "rebuild ms       %.0f beside the mapper's loop (one keyframe moved 3 cm: the octree cast again), "
        "then "
        "%.0f to carve the cloud; the loop's longest turn meanwhile %.0f ms\n",
        rebuild_ms, carve.elapsedMs(), longest_turn_ms);
  }
  return 0;
}

void addBenchMapperOptions(ArgParser& args) {
  args.addOption("dataset", "DIR",
                 "TUM-format folder; keyframes at its groundtruth.txt poses unless --poses (no masks)");
  args.addOption(
      "poses", "FILE",
      "with --dataset: camera poses (TUM format, camera to world) instead of groundtruth.txt, e.g. "
      "a run's trajectory.txt (Bonn's ground truth is its marker body's, not the camera's)");
  args.addFlag("synthetic", "use the built-in synthetic scene instead (ground-truth masks)");
  args.addOption("camera", "FILE", "camera YAML; default: DIR/camera.yaml, else by the folder's name");
  args.addOption("every", "N", "a keyframe every N frames", "10");
  args.addOption("keyframes", "N", "stop after N keyframes");
  args.addOption("pixel-step", "N", "override mapper.cloud.pixel_step");
  args.addOption("loops", "N", "feed the keyframes N times (the same room mapped over and over)", "1");
  args.addOption("config", "FILE", "mapper YAML", configDir() + "/mapper.yaml");
  args.addOption("out", "DIR", "also write the map files here");
}

}  // namespace bmp::mapper

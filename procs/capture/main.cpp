// bmp-capture: plays a TUM-format folder, or the synthetic scene, as RGBD_FRAME messages.
#include <filesystem>
#include <memory>
#include <set>
#include <sstream>

#include <bmp/process_status_t.hpp>

#include "bmp/common/camera_config.hpp"
#include "bmp/common/log.hpp"
#include "bmp/common/timing.hpp"
#include "bmp/lcm/process.hpp"
#include "capture/camera_selection.hpp"
#include "capture/lcm/frame_player.hpp"
#include "capture/selected_source.hpp"
#include "capture/synthetic_config.hpp"
#include "capture/synthetic_source.hpp"
#include "capture/tum_source.hpp"

namespace {

using namespace bmp;
using namespace bmp::capture;

void addOptions(ArgParser& args) {
  args.addOption("dataset", "DIR",
                 "TUM-format folder (rgb.txt, depth.txt, optional groundtruth.txt); "
                 "without it the synthetic scene plays");
  args.addOption("camera", "FILE", "camera YAML; default: DIR/camera.yaml, else chosen by the folder name");
  args.addOption("synthetic-config", "FILE", "synthetic scene YAML (default: capture.synthetic_config)");
  args.addOption("mode", "MODE", "realtime | fast | lockstep (default: capture.mode)");
  args.addOption("speed", "X", "realtime mode: recorded rate x X (default: capture.speed)");
  args.addOption("start", "N", "first associated frame to play", "0");
  args.addOption("end", "N", "one past the last frame to play; -1 = all", "-1");
  args.addOption("every", "K", "play every K-th frame", "1");
  args.addOption("verify", "HOW", "header | decode: how images are checked before publishing");
  args.addOption("ack-channels", "LIST",
                 "lockstep: comma-separated channels that must all answer a frame "
                 "before the next (default: capture.ack_channels)");
  args.addOption("groundtruth-out", "FILE", "write the ground truth of the played sequence (TUM format)");
  args.addOption("masks-out", "DIR", "synthetic scene: write the dynamic-object masks as PNG");
  args.addOption("wait-for", "NAMES",
                 "comma-separated process names whose heartbeat must be seen before "
                 "the first frame (e.g. bmp-tracker,bmp-detector)");
  args.addEpilog(
      "Examples:\n"
      "  bmp-capture --dataset ../shared/data/rgbd_bonn_crowd --mode realtime\n"
      "  bmp-capture --mode lockstep --groundtruth-out out/gt.txt      # synthetic scene\n"
      "Skipped files (missing, corrupt, wrong size) are reported with the reason and counted.\n");
}

// The configuration value is always read (so finish() accepts the file); the command line wins.
std::string overridden(const ArgParser& args, const std::string& option, const std::string& config_value) {
  return args.given(option) ? args.value(option) : config_value;
}

void waitForProcesses(ProcessContext& ctx, const std::string& names, double timeout_s) {
  // Shared with the handler: the subscription outlives this function (LCM keeps it to the end).
  const auto pending = std::make_shared<std::set<std::string>>();
  std::stringstream list(names);
  for (std::string name; std::getline(list, name, ',');)
    if (!name.empty()) pending->insert(name);
  if (pending->empty()) return;
  ctx.lcm.subscribe<process_status_t>(
      channels::kProcessStatus,
      [pending](const process_status_t& msg, const ReceivedInfo&) { pending->erase(msg.name); });
  log::info("waiting for heartbeats of ", names);
  const Stopwatch watch;
  while (!pending->empty() && !ctx.stop.requested()) {
    if (watch.elapsedMs() > timeout_s * 1000.0) {
      std::string missing;
      for (const auto& n : *pending) missing += (missing.empty() ? "" : ", ") + n;
      throw std::runtime_error("no heartbeat from " + missing + " within " + std::to_string(timeout_s) +
                               " s");
    }
    ctx.lcm.handle(50);
  }
}

std::unique_ptr<FrameSource> makeSource(ProcessContext& ctx, const Config& cfg) {
  const auto& args = ctx.args;
  const auto warn = [](const std::string& m) { log::warn(m); };
  const std::string synthetic_file = cfg.get<std::string>("synthetic_config", "synthetic.yaml");
  const double max_difference = cfg.get<double>("max_association_difference_s", 0.02);
  const std::string verify = overridden(args, "verify", cfg.get<std::string>("verify", "header"));
  const FrameSelection selection{args.integer("start"), args.integer("end"), args.integer("every")};
  if (!args.given("dataset")) {
    const std::string path =
        args.given("synthetic-config") ? args.value("synthetic-config") : configDir() + "/" + synthetic_file;
    const Config synthetic = Config::fromFile(path);
    SyntheticSceneConfig scene_config = syntheticSceneFromConfig(synthetic.section("synthetic"));
    synthetic.finish();
    // Frames past --end are never rendered; --start/--every are applied by index.
    if (selection.end >= 0)
      scene_config.num_frames = static_cast<int>(std::min<int64_t>(scene_config.num_frames, selection.end));
    return std::make_unique<SelectedSource>(std::make_unique<SyntheticSource>(scene_config), selection);
  }
  const std::string dir = args.value("dataset");
  // The folder first: a missing folder must be reported as such, not as an unknown camera.
  SequenceIndex index = indexSequence(dir, max_difference);
  const SequenceCamera selected = selectCamera(dir, args.value("camera"), configDir() + "/cameras");
  const CameraIntrinsics& camera = selected.intrinsics;
  log::info("camera from ", selected.file);
  TumSourceOptions options;
  options.selection = selection;
  options.verify = parseVerifyMode(verify);
  options.warn = warn;
  log::info(dir, ": ", index.frames.size(), " associated pairs from ", index.rgb_entries, " colour and ",
            index.depth_entries, " depth entries",
            index.groundtruth.empty() ? ", no ground truth" : ", with ground truth");
  return std::make_unique<TumSource>(std::move(index), camera, std::move(options));
}

int run(ProcessContext& ctx) {
  const Config cfg = ctx.config.section("capture");
  PlayerOptions options;
  options.channel = cfg.get<std::string>("channel", options.channel);
  const auto ack_channels = cfg.get<std::vector<std::string>>("ack_channels", options.ack_channels);
  options.ack_channels = ack_channels;
  if (ctx.args.given("ack-channels")) {
    options.ack_channels.clear();
    std::stringstream list(ctx.args.value("ack-channels"));
    for (std::string name; std::getline(list, name, ',');)
      if (!name.empty()) options.ack_channels.push_back(name);
  }
  options.mode = parseRateMode(overridden(ctx.args, "mode", cfg.get<std::string>("mode", "realtime")));
  // Without an answer to wait for, lockstep would silently play as fast as it can and consumers would drop.
  if (options.mode == RateMode::kLockstep && options.ack_channels.empty())
    throw ConfigError(cfg.origin() +
                      ": mode lockstep needs at least one answer channel (capture.ack_channels "
                      "or --ack-channels)");
  const double speed = cfg.get<double>("speed", options.speed);
  options.speed = ctx.args.given("speed") ? ctx.args.number("speed") : speed;
  options.lockstep_timeout_s = cfg.get<double>("lockstep_timeout_s", options.lockstep_timeout_s);
  options.progress_every_s = cfg.get<double>("progress_every_s", options.progress_every_s);
  options.masks_out = ctx.args.value("masks-out");
  const double wait_timeout_s = cfg.get<double>("wait_timeout_s", 30.0);
  std::unique_ptr<FrameSource> source = makeSource(ctx, cfg);
  finishConfig(ctx);

  waitForProcesses(ctx, ctx.args.value("wait-for"), wait_timeout_s);
  ctx.status.tick(true);
  FramePlayer player(ctx.lcm, ctx.stop, ctx.status, options);
  PlayerSummary summary = player.play(*source);

  if (ctx.args.given("groundtruth-out")) {
    const std::string out = ctx.args.value("groundtruth-out");
    const auto* tum = dynamic_cast<const TumSource*>(source.get());
    const Trajectory& gt = tum ? tum->index().groundtruth : summary.groundtruth;
    if (gt.empty()) {
      log::warn("no ground truth for ", source->name(), "; ", out, " not written");
    } else {
      writeTumTrajectory(out, gt);
      log::info("ground truth (", gt.size(), " poses) written to ", out);
    }
  }
  return summary.published > 0 ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  return bmp::runProcess(
      argc, argv,
      {"bmp-capture",
       "Plays a TUM-format RGB-D folder, or the built-in synthetic scene, as RGBD_FRAME "
       "messages over LCM, in real time, as fast as possible, or in lockstep with the tracker.",
       "capture.yaml", addOptions, run});
}

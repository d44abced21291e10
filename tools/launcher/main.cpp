// bmp-run: starts the processes of a run, plays a sequence, stops them cleanly, gathers their outputs into
// out/<run>/ and evaluates the trajectory against the ground truth.
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <iostream>
#include <memory>

#include "bmp/common/arg_parser.hpp"
#include "bmp/common/atomic_file.hpp"
#include "bmp/common/child_process.hpp"
#include "bmp/common/log.hpp"
#include "bmp/common/timing.hpp"
#include "bmp/common/tool_main.hpp"
#include "bmp/lcm/lcm_node.hpp"
#include "bmp/lcm/process.hpp"
#include "launcher/launch_plan.hpp"
#include "launcher/output_relay.hpp"
#include "launcher/run_monitor.hpp"

namespace {

namespace fs = std::filesystem;
using namespace bmp;
using namespace bmp::launcher;

struct Launched {
  std::string name;
  std::unique_ptr<ChildProcess> child;
};

std::unique_ptr<ChildProcess> start(const ProcessCommand& cmd, const fs::path& logs, OutputRelay& relay,
                                    bool echo) {
  if (!fs::exists(cmd.argv[0]))
    throw std::runtime_error(cmd.argv[0] + ": not built (run tools/run, or build it)");
  auto child = std::make_unique<ChildProcess>(cmd.argv, ChildProcess::Output::kPipe);
  relay.follow(child->outputFd(), cmd.name, (logs / (cmd.name + ".log")).string(), echo);
  std::string line;
  for (const auto& a : cmd.argv) line += (line.empty() ? "" : " ") + a;
  log::info("started ", cmd.name, " (pid ", child->pid(), "): ", line);
  return child;
}

void writeSummaryFile(const std::string& path, const std::string& text) {
  try {
    writeFileAtomically(path, text);
  } catch (const FileWriteError& e) {
    log::warn(e.what(), " (the run summary)");
  }
}

int evaluate(const LaunchPlan& plan, const RunRequest& request, OutputRelay& relay, const fs::path& logs) {
  if (!fs::exists(plan.groundtruth_path)) {
    log::info("no ground truth: nothing to evaluate");
    return 0;
  }
  if (!fs::exists(plan.trajectory_path)) {
    log::info("no trajectory was written (no tracker in this run): nothing to evaluate");
    return 0;
  }
  const fs::path out(request.out_dir);
  ProcessCommand eval{
      "bmp-eval",
      {(fs::path(request.bin_dir) / "bmp-eval").string(), "--gt", plan.groundtruth_path, "--est",
       plan.trajectory_path, "--json", (out / "eval.json").string(), "--plot-dir", (out / "plots").string()}};
  auto child = start(eval, logs, relay, true);
  while (relay.pump(100)) {
  }
  return child->wait(60).value_or(1);
}

int launch(const ArgParser& args) {
  const std::string config_path = args.value("config");
  const Config config = Config::fromFile(config_path);
  const RunSettings settings = runSettingsFromConfig(config.section("run"));
  config.finish();

  RunRequest request;
  request.dataset = args.value("dataset");
  if (!request.dataset.empty() && !fs::is_directory(request.dataset))
    throw std::runtime_error(request.dataset + ": no such dataset folder");
  request.camera = args.value("camera");
  request.mode = args.value("mode");
  request.speed = args.value("speed");
  request.frames = args.given("frames") ? args.integer("frames") : -1;
  request.lcm_url = resolveLcmUrl(args.value("lcm-url"));
  request.bin_dir = fs::canonical("/proc/self/exe").parent_path().string();
  request.out_dir = args.given("out")
                        ? args.value("out")
                        : (fs::path(settings.output_root) / runFolderName(request.dataset)).string();
  const fs::path logs = fs::path(request.out_dir) / "logs";
  fs::create_directories(logs);
  if (!args.given("out")) {
    const fs::path latest = fs::path(settings.output_root) / "latest";
    std::error_code ignored;
    fs::remove(latest, ignored);
    fs::create_directory_symlink(fs::path(request.out_dir).filename(), latest, ignored);
  }
  request.out_dir = fs::absolute(request.out_dir).string();
  const LaunchPlan plan = makePlan(settings, request);
  log::info("run folder ", request.out_dir, ", LCM ", request.lcm_url);

  // Every executable first: a missing one must not leave the others half started.
  for (const auto& cmd : plan.processes)
    if (!fs::exists(cmd.argv[0]))
      throw std::runtime_error(cmd.argv[0] + ": not built (run tools/run, or build it)");
  StopSignal stop;
  OutputRelay relay;
  // Listening before anything starts, so the summary hears every frame's answer.
  RunMonitor monitor(request.lcm_url, settings.pose_channel, settings.detections_channel);
  std::vector<Launched> launched;
  for (const auto& cmd : plan.processes) launched.push_back({cmd.name, start(cmd, logs, relay, false)});
  Launched capture{"bmp-capture", start(plan.capture, logs, relay, true)};

  bool failed_early = false;
  while (capture.child->running()) {
    relay.pump(100);
    if (stop.requested()) {
      log::warn("interrupted: stopping the run");
      capture.child->signal(SIGINT);
    }
    for (auto& p : launched) {
      if (!p.child->running() && !failed_early) {
        log::error(p.name, " ended early with status ", *p.child->exitStatus(), "; see ",
                   (logs / (p.name + ".log")).string());
        failed_early = true;
        capture.child->signal(SIGINT);
      }
    }
  }
  const Stopwatch drain;
  while (drain.elapsedMs() < settings.drain_s * 1000.0 && !stop.requested()) relay.pump(50);

  int worst = 0;
  const auto record = [&worst](const std::string& name, int status) {
    log::info(name, " exited with status ", status);
    if (status != 0) worst = 1;
  };
  record("bmp-capture", *capture.child->exitStatus());
  for (auto& p : launched) {
    p.child->signal(SIGINT);
  }
  for (auto& p : launched) {
    const Stopwatch waited;
    while (p.child->running() && waited.elapsedMs() < settings.stop_timeout_s * 1000.0) relay.pump(50);
    if (p.child->running()) log::warn(p.name, " did not stop within ", settings.stop_timeout_s, " s: killed");
    record(p.name, p.child->stop(0.5));
  }
  while (relay.pump(50)) {
  }

  const RunSummary summary = monitor.summary();
  writeSummaryFile((fs::path(request.out_dir) / "summary.json").string(), formatSummaryJson(summary));

  if (settings.evaluate && !args.flag("no-eval")) {
    if (worst == 0) {
      if (evaluate(plan, request, relay, logs) != 0) worst = 1;
    } else if (fs::exists(plan.trajectory_path)) {
      // What was tracked before the failure is still worth a look; the run stays failed.
      log::warn("a process failed: evaluating the poses written up to the failure");
      evaluate(plan, request, relay, logs);
    }
  }
  std::cout << formatSummaryText(summary) << std::flush;  // last, where the eye lands
  log::info(worst == 0 ? "run finished: " : "run FAILED: ", request.out_dir, " (logs in ", logs.string(),
            ")");
  return worst;
}

}  // namespace

int main(int argc, char** argv) {
  ArgParser args(
      "bmp-run",
      "Runs the BMP-SLAM pipeline: starts the processes listed in the run configuration, plays the "
      "synthetic scene or a TUM-format folder through bmp-capture, stops everything cleanly when the "
      "sequence ends, and evaluates the trajectory against the ground truth (ATE, RPE, plots).");
  args.addOption("dataset", "DIR", "TUM-format folder; without it the built-in synthetic scene plays");
  args.addOption("camera", "FILE", "camera YAML for the dataset (default: chosen by bmp-capture)");
  args.addOption("config", "FILE", "run configuration", configDir() + "/run.yaml");
  args.addOption("out", "DIR", "run folder (default: <output_root>/<time>_<sequence>, linked as latest)");
  args.addOption("mode", "MODE", "capture mode: lockstep | realtime | fast (default: run.mode)");
  args.addOption("speed", "X", "realtime mode: recorded rate x X");
  args.addOption("frames", "N", "play only the first N frames");
  args.addOption("lcm-url", "URL", "LCM URL for every process; else $LCM_DEFAULT_URL, else the default");
  args.addFlag("no-eval", "do not evaluate");
  args.addEpilog(
      "Outputs in the run folder: trajectory.txt (TUM), groundtruth.txt, eval.json, plots/*.png,\n"
      "logs/<process>.log. Exit status is non-zero if any process failed.\n");
  return runTool(args, argc, argv, launch);
}

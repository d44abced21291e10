#include "launcher/run_session.hpp"

#include <chrono>
#include <csignal>
#include <filesystem>
#include <iostream>
#include <limits>
#include <memory>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <bmp/process_status_t.hpp>

#include "bmp/common/arg_range.hpp"
#include "bmp/common/atomic_file.hpp"
#include "bmp/common/child_process.hpp"
#include "bmp/common/log.hpp"
#include "bmp/common/timing.hpp"
#include "bmp/lcm/lcm_node.hpp"
#include "bmp/lcm/process.hpp"
#include "capture/camera_selection.hpp"
#include "capture/pacer.hpp"
#include "capture/tum_sequence.hpp"
#include "launcher/launch_plan.hpp"
#include "launcher/output_relay.hpp"
#include "launcher/run_folder.hpp"
#include "launcher/run_monitor.hpp"

namespace bmp::launcher {

namespace {

namespace fs = std::filesystem;

constexpr long long kMaxFrames = 100000000, kMaxLoops = 1000000;

struct Launched {
  std::string name;
  std::unique_ptr<ChildProcess> child;
};

// A run's processes and what watches them, set up in this order and torn down in reverse (children first).
struct Session {
  Session(const RunSettings& settings, const RunRequest& request)
      : monitor(request.lcm_url, settings.pose_channel, settings.detections_channel,
                settings.status_channel) {}

  StopSignal stop;
  OutputRelay relay;
  // Listening before anything starts, so the summary hears every frame's answer.
  RunMonitor monitor;
  fs::path logs;                   // set once the run folder is made
  std::vector<Launched> launched;  // every process but capture
  Launched capture{"bmp-capture", nullptr};
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

// A usage error naming the option: nothing has started and no folder was made when it is thrown.
void require(bool ok, const ArgParser& args, const std::string& option, const std::string& rule) {
  if (!ok) throw ArgError("bmp-run: --" + option + " '" + args.value(option) + "': " + rule);
}

// The folder's lists and camera as bmp-capture will read them: one it would refuse at start-up must not
// set aside the earlier run in --out (two such attempts would lose it) nor start the other processes.
// Pairing colour with depth is capture's, by its own tolerance: here any pair will do.
void checkDataset(const ArgParser& args, const std::string& dataset, const std::string& camera) {
  try {
    capture::indexSequence(dataset, std::numeric_limits<double>::infinity());
    capture::selectCamera(dataset, camera, configDir() + "/cameras");
  } catch (const std::exception& e) {  // SequenceError or ConfigError, naming the file and line or key
    throw ArgError("bmp-run: --dataset '" + args.value("dataset") + "': " + e.what());
  }
}

// Every option checked before anything starts: a run that cannot be what was asked must not begin.
RunRequest requestFromArgs(const ArgParser& args, const RunSettings& settings) {
  RunRequest request;
  request.dataset = args.value("dataset");
  require(request.dataset.empty() || fs::is_directory(request.dataset), args, "dataset",
          fs::exists(request.dataset) ? "not a folder" : "no such folder");
  request.camera = args.value("camera");
  require(request.camera.empty() || fs::is_regular_file(request.camera), args, "camera", "no such file");
  if (!request.dataset.empty()) checkDataset(args, request.dataset, request.camera);
  request.mode = args.value("mode");
  require(!args.given("mode") || isCaptureMode(request.mode), args, "mode",
          "must be lockstep, realtime or fast");
  request.speed = args.value("speed");
  if (args.given("speed")) numberIn(args, "speed", capture::Pacer::kMinSpeed, capture::Pacer::kMaxSpeed);
  request.frames = args.given("frames") ? integerIn(args, "frames", 1, kMaxFrames) : -1;
  request.loops = args.value("loop");
  if (args.given("loop")) integerIn(args, "loop", 1, kMaxLoops);
  request.lcm_url = resolveLcmUrl(args.value("lcm-url"));
  request.bin_dir = fs::canonical("/proc/self/exe").parent_path().string();
  request.out_dir =
      fs::absolute(args.given("out") ? fs::path(args.value("out"))
                                     : fs::path(settings.output_root) / runFolderName(request.dataset))
          .string();
  return request;
}

// Creates the run folder and its logs/; a folder chosen by us (not by --out) is also linked as
// <output_root>/latest. Returns the logs folder.
fs::path prepareRunFolder(const RunRequest& request, const RunSettings& settings, bool link_latest) {
  const fs::path out(request.out_dir);
  const fs::path logs = out / "logs";
  std::error_code ec;
  fs::create_directories(out, ec);  // before an earlier run is moved: a folder we cannot make displaces none
  if (ec) throw ArgError("bmp-run: --out '" + request.out_dir + "': cannot make the folder: " + ec.message());
  const bool replaces = fs::exists(out / kPreviousRunFolder, ec);
  if (setAsideEarlierRun(request.out_dir))
    log::info("the earlier run in ", request.out_dir, " is kept in ", (out / kPreviousRunFolder).string(),
              replaces ? " (replacing the one kept there)" : "");
  fs::create_directories(logs, ec);
  if (ec) throw std::runtime_error(logs.string() + ": cannot make the folder: " + ec.message());
  if (link_latest) {
    const fs::path latest = fs::path(settings.output_root) / "latest";
    std::error_code ignored;
    fs::remove(latest, ignored);
    fs::create_directory_symlink(fs::path(request.out_dir).filename(), latest, ignored);
  }
  return logs;
}

// Every executable first: a missing one must not leave the others half started.
void checkBuilt(const LaunchPlan& plan) {
  for (const auto& cmd : plan.processes)
    if (!fs::exists(cmd.argv[0]))
      throw std::runtime_error(cmd.argv[0] + ": not built (run tools/run, or build it)");
}

void startProcesses(Session& s, const LaunchPlan& plan) {
  for (const auto& cmd : plan.processes) s.launched.push_back({cmd.name, start(cmd, s.logs, s.relay, false)});
  s.capture.child = start(plan.capture, s.logs, s.relay, true);
}

// Until capture ends. An interrupt, or another process ending early, asks capture to stop (SIGINT), so the
// run winds down the normal way. A process ending after the user's interrupt is no failure: Ctrl-C in a
// terminal reaches every process of the run at once.
void superviseCapture(Session& s) {
  bool failed_early = false;
  bool interrupt_seen = false;
  while (s.capture.child->running()) {
    s.relay.pump(100);
    if (s.stop.requested() && !interrupt_seen) {
      interrupt_seen = true;
      log::warn("interrupted by the user: stopping the run");
      s.capture.child->signal(SIGINT);
    }
    for (auto& p : s.launched) {
      if (!p.child->running() && !failed_early && !s.stop.requested()) {
        log::error(p.name, " ended early with status ", *p.child->exitStatus(), "; see ",
                   (s.logs / (p.name + ".log")).string());
        failed_early = true;
        s.capture.child->signal(SIGINT);
      }
    }
  }
}

// Lets the consumers finish the last frames, then stops each with SIGINT (killed after stop_timeout_s).
// Returns 0 when capture and every process exited with status 0, else 1.
int stopOthers(Session& s, const RunSettings& settings) {
  const Stopwatch drain;
  while (drain.elapsedMs() < settings.drain_s * 1000.0 && !s.stop.requested()) s.relay.pump(50);

  int worst = 0;
  const auto record = [&worst](const std::string& name, int status) {
    log::info(name, " exited with status ", status);
    if (status != 0) worst = 1;
  };
  // Stopped by the user, each process still gets its SIGINT and its time to write what it owes.
  record(s.capture.name, *s.capture.child->exitStatus());
  for (auto& p : s.launched) p.child->signal(SIGINT);
  for (auto& p : s.launched) {
    const Stopwatch waited;
    while (p.child->running() && waited.elapsedMs() < settings.stop_timeout_s * 1000.0) s.relay.pump(50);
    if (p.child->running()) log::warn(p.name, " did not stop within ", settings.stop_timeout_s, " s: killed");
    record(p.name, p.child->stop(0.5));
  }
  while (s.relay.pump(50)) {
  }
  return worst;
}

// Runs bmp-eval on the trajectory against the ground truth; its exit status (0 when there is nothing to
// evaluate).
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
  // The tracker's frame log, when the run wrote one, becomes a picture beside the error plots.
  if (fs::exists(out / "frames.tsv")) {
    eval.argv.push_back("--frame-log");
    eval.argv.push_back((out / "frames.tsv").string());
  }
  auto child = start(eval, logs, relay, true);
  while (relay.pump(100)) {
  }
  return child->wait(60).value_or(1);
}

// The conventional status of a process stopped by a signal: 130 for SIGINT, 143 for SIGTERM.
int interruptedStatus(const StopSignal& stop) {
  return 128 + (stop.signalNumber() > 0 ? stop.signalNumber() : SIGINT);
}

// Returns the run's exit status given the processes' (worst): a failed evaluation fails the run. A run the
// user stopped evaluates what was tracked and keeps the interrupt's status, whatever the processes said.
int evaluateRun(Session& s, const LaunchPlan& plan, const RunRequest& request, int worst) {
  if (s.stop.requested()) {
    if (fs::exists(plan.trajectory_path)) {
      log::info("stopped by the user: evaluating the poses written up to the interrupt");
      evaluate(plan, request, s.relay, s.logs);
    }
    return interruptedStatus(s.stop);
  }
  if (worst == 0) return evaluate(plan, request, s.relay, s.logs) != 0 ? 1 : 0;
  if (fs::exists(plan.trajectory_path)) {
    // What was tracked before the failure is still worth a look; the run stays failed.
    log::warn("a process failed: evaluating the poses written up to the failure");
    evaluate(plan, request, s.relay, s.logs);
  }
  return worst;
}

// The processes have exited; their last heartbeats (sent just before) may still be on the way to the
// monitor's thread. Waits up to timeout_s for one final heartbeat per process started.
RunSummary finalSummary(const Session& s, double timeout_s) {
  const Stopwatch waited;
  while (true) {
    RunSummary summary = s.monitor.summary();
    std::size_t finished = 0;
    for (const auto& [key, p] : summary.processes) finished += p.state == process_status_t::STATE_FINISHED;
    if (finished >= s.launched.size() + 1 || waited.elapsedMs() > timeout_s * 1000.0) return summary;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

void writeSummaryFile(const std::string& path, const std::string& text) {
  try {
    writeFileAtomically(path, text);
  } catch (const FileWriteError& e) {
    log::warn(e.what(), " (the run summary)");
  }
}

}  // namespace

int runSession(const ArgParser& args) {
  const Config config = Config::fromFile(args.value("config"));
  const RunSettings settings = runSettingsFromConfig(config.section("run"));
  config.finish();

  const RunRequest request = requestFromArgs(args, settings);
  const LaunchPlan plan = makePlan(settings, request);
  checkBuilt(plan);  // before the run folder: a misspelt process in run.yaml touches no earlier run
  // LCM opened before the run folder too: a run that cannot listen (a wrong URL, no multicast route)
  // displaces no earlier run.
  Session session(settings, request);
  session.logs = prepareRunFolder(request, settings, !args.given("out"));
  const fs::path& logs = session.logs;
  log::info("run folder ", request.out_dir, ", LCM ", request.lcm_url);

  startProcesses(session, plan);
  superviseCapture(session);
  int worst = stopOthers(session, settings);

  const RunSummary summary = finalSummary(session, 1.0);
  writeSummaryFile((fs::path(request.out_dir) / "summary.json").string(), formatSummaryJson(summary));
  if (settings.evaluate && !args.flag("no-eval"))
    worst = evaluateRun(session, plan, request, worst);
  else if (session.stop.requested())
    worst = interruptedStatus(session.stop);
  std::cout << formatSummaryText(summary) << std::flush;  // last, where the eye lands
  const char* verdict = session.stop.requested() ? "run stopped by the user: "
                        : worst == 0             ? "run finished: "
                                                 : "run FAILED: ";
  log::info(verdict, request.out_dir, " (logs in ", logs.string(), ")");
  return worst;
}

}  // namespace bmp::launcher

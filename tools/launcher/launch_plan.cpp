#include "launcher/launch_plan.hpp"

#include <ctime>
#include <filesystem>

namespace bmp::launcher {

namespace {
std::string expand(std::string text, const RunRequest& request, const std::string& mode) {
  const auto replace = [&text](const std::string& key, const std::string& value) {
    for (std::size_t pos; (pos = text.find(key)) != std::string::npos;) text.replace(pos, key.size(), value);
  };
  replace("{out}", request.out_dir);
  replace("{dataset}", request.dataset);
  // Consumers must see every frame when capture waits for them, and only the newest when it does not.
  replace("{frame_policy}", mode == "lockstep" ? "every" : "latest");
  return text;
}
}  // namespace

bool isCaptureMode(const std::string& mode) {
  return mode == "lockstep" || mode == "realtime" || mode == "fast";
}

RunSettings runSettingsFromConfig(const Config& c) {
  RunSettings s;
  s.output_root = c.get<std::string>("output_root", s.output_root);
  s.mode = c.get<std::string>("mode", s.mode);
  c.check(isCaptureMode(s.mode), "mode", "must be lockstep, realtime or fast, got '" + s.mode + "'");
  s.stop_timeout_s = c.get<double>("stop_timeout_s", s.stop_timeout_s);
  s.drain_s = c.get<double>("drain_s", s.drain_s);
  s.evaluate = c.get<bool>("evaluate", s.evaluate);
  s.pose_channel = c.get<std::string>("pose_channel", s.pose_channel);
  s.detections_channel = c.get<std::string>("detections_channel", s.detections_channel);
  s.status_channel = c.get<std::string>("status_channel", s.status_channel);
  const Config processes = c.section("processes");
  for (const auto& name : processes.keys())
    s.processes.push_back({name, processes.get<std::vector<std::string>>(name, {})});
  s.capture_args = c.get<std::vector<std::string>>("capture_args", {});
  return s;
}

LaunchPlan makePlan(const RunSettings& settings, const RunRequest& request) {
  namespace fs = std::filesystem;
  LaunchPlan plan;
  const auto exe = [&](const std::string& name) { return (fs::path(request.bin_dir) / name).string(); };
  const std::string mode = request.mode.empty() ? settings.mode : request.mode;
  std::string names;
  for (const auto& p : settings.processes) {
    ProcessCommand cmd{p.name, {exe(p.name), "--lcm-url", request.lcm_url}};
    for (const auto& a : p.argv) cmd.argv.push_back(expand(a, request, mode));
    plan.processes.push_back(cmd);
    names += (names.empty() ? "" : ",") + p.name;
  }
  plan.groundtruth_path = (fs::path(request.out_dir) / "groundtruth.txt").string();
  plan.trajectory_path = (fs::path(request.out_dir) / "trajectory.txt").string();
  ProcessCommand& cap = plan.capture;
  cap.name = "bmp-capture";
  cap.argv = {exe("bmp-capture"),  "--lcm-url",          request.lcm_url, "--mode", mode,
              "--groundtruth-out", plan.groundtruth_path};
  if (!request.dataset.empty()) cap.argv.insert(cap.argv.end(), {"--dataset", request.dataset});
  if (!request.camera.empty()) cap.argv.insert(cap.argv.end(), {"--camera", request.camera});
  if (!request.speed.empty()) cap.argv.insert(cap.argv.end(), {"--speed", request.speed});
  if (request.frames >= 0) cap.argv.insert(cap.argv.end(), {"--end", std::to_string(request.frames)});
  if (!request.loops.empty()) cap.argv.insert(cap.argv.end(), {"--loop", request.loops});
  // One entry per process started: capture counts distinct processes, so a name listed twice waits for two.
  if (!names.empty()) cap.argv.insert(cap.argv.end(), {"--wait-for", names});
  for (const auto& a : settings.capture_args) cap.argv.push_back(expand(a, request, mode));
  return plan;
}

std::string runFolderName(const std::string& dataset) {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char stamp[32];
  std::strftime(stamp, sizeof(stamp), "%Y%m%d-%H%M%S", &utc);
  std::string name = dataset.empty()
                         ? "synthetic"
                         : std::filesystem::absolute(dataset).lexically_normal().filename().string();
  if (name.empty()) name = "dataset";
  return std::string(stamp) + "_" + name;
}

}  // namespace bmp::launcher

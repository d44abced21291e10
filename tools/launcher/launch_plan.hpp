#pragma once
// What a run starts: the processes named in config/run.yaml, then bmp-capture, each with its command line,
// and where their outputs go.
#include <string>
#include <vector>

#include "bmp/common/config.hpp"
#include "bmp/lcm/channels.hpp"

namespace bmp::launcher {

struct ProcessCommand {
  std::string name;               // e.g. "bmp-tracker"
  std::vector<std::string> argv;  // argv[0] is the executable's path
};

struct RunRequest {
  std::string dataset;    // "" = synthetic scene
  std::string camera;     // "" = capture chooses
  std::string mode;       // capture mode; "" = run.yaml's
  std::string speed;      // "" = default
  long long frames = -1;  // -1 = the whole sequence
  std::string loops;      // "" = once
  std::string lcm_url;
  std::string out_dir;  // the run's folder
  std::string bin_dir;  // where the executables are
};

struct RunSettings {
  std::string output_root = "out";
  std::string mode = "lockstep";
  double stop_timeout_s = 15.0;
  double drain_s = 1.0;  // after capture ends, before SIGINT: lets consumers finish
  bool evaluate = true;
  std::string pose_channel = channels::kPose;              // heard for the run summary
  std::string detections_channel = channels::kDetections;  // likewise
  std::string status_channel = channels::kProcessStatus;   // likewise: each process's frame counts
  std::vector<ProcessCommand> processes;                   // args from config, before placeholder expansion
  std::vector<std::string> capture_args;
};

// lockstep, realtime or fast: the capture modes a run may ask for.
bool isCaptureMode(const std::string& mode);

// Reads the "run" section. Placeholders in arguments, expanded by makePlan: {out} the run folder, {dataset}
// the dataset folder, {frame_policy} "every" in lockstep mode and "latest" otherwise.
RunSettings runSettingsFromConfig(const Config& run_section);

struct LaunchPlan {
  std::vector<ProcessCommand> processes;  // started first, in order
  ProcessCommand capture;                 // started once they are up; its end ends the run
  std::string groundtruth_path;
  std::string trajectory_path;  // the tracker's trajectory, evaluated when both exist
};

LaunchPlan makePlan(const RunSettings& settings, const RunRequest& request);

// "20261122-021503_rgbd_bonn_crowd" style name for a run folder.
std::string runFolderName(const std::string& dataset);

}  // namespace bmp::launcher

#pragma once
// Helpers for tests that run the real processes over a real udpm:// LCM URL.
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "bmp/common/child_process.hpp"
#include "lcm_url.hpp"
#include "run_command.hpp"
#include "shared_data.hpp"

namespace bmp::test {

struct ReportLine {
  long long seq = 0, utime = 0, depth_utime = 0, color_bytes = 0, depth_bytes = 0;
  int decoded = 0;
};

inline std::vector<ReportLine> readReport(const std::string& path) {
  std::vector<ReportLine> lines;
  std::ifstream in(path);
  ReportLine r;
  while (in >> r.seq >> r.utime >> r.depth_utime >> r.color_bytes >> r.depth_bytes >> r.decoded)
    lines.push_back(r);
  return lines;
}

// The pid of a running process (e.g. "bmp-tracker") whose command line mentions `marker` (its run folder), or
// -1.
inline pid_t findProcess(const std::string& name, const std::string& marker) {
  for (const auto& entry : std::filesystem::directory_iterator("/proc")) {
    const std::string pid = entry.path().filename().string();
    if (pid.find_first_not_of("0123456789") != std::string::npos) continue;
    std::string cmdline = readText((entry.path() / "cmdline").string());
    std::replace(cmdline.begin(), cmdline.end(), '\0', ' ');
    if (cmdline.find("/" + name + " ") != std::string::npos && cmdline.find(marker) != std::string::npos)
      return static_cast<pid_t>(std::stol(pid));
  }
  return -1;
}

// A run.yaml for bmp-run with capture and the tracker only (lockstep, short drain and stop), written into
// dir: its runs go under output_root, the tracker gets tracker_args. Returns the file's path.
inline std::filesystem::path trackerOnlyRunConfig(const std::filesystem::path& dir,
                                                  const std::filesystem::path& output_root,
                                                  const std::string& tracker_args) {
  const std::filesystem::path path = dir / "run.yaml";
  std::ofstream(path) << "run:\n  output_root: " << output_root.string()
                      << "\n  mode: lockstep\n  drain_s: 0.2\n  stop_timeout_s: 5.0\n  evaluate: true\n"
                      << "  processes:\n    bmp-tracker: [" << tracker_args << "]\n"
                      << "  capture_args: [--ack-channels, SLAM_POSE]\n";
  return path;
}

}  // namespace bmp::test

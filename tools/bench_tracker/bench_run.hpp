#pragma once
// bmp-bench-tracker's run: tracks a TUM-format folder frame by frame through the offline runner (no LCM),
// then prints the tracking time per frame, frames lost and the ATE against the folder's groundtruth.txt.
#include "bmp/common/arg_parser.hpp"

namespace bmp::tracker {

// The options runBenchTracker reads.
void addBenchTrackerOptions(ArgParser& args);

// Runs the benchmark and prints its summary on stdout (progress on stderr); returns the exit code (0).
// Throws ConfigError for a bad --config and std::runtime_error for what fails while working.
int runBenchTracker(const ArgParser& args);

}  // namespace bmp::tracker

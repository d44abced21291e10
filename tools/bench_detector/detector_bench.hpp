#pragma once
// bmp-bench-detector's run: each model's per-frame time (decode + letterbox + inference + NMS) on frames
// read into memory first, as median, p95, mean and the ratio of the median to the 30 ms target.
#include "bmp/common/arg_parser.hpp"

namespace bmp::detect_tools {

// Reads the options bmp-bench-detector's main declares (--input, --frames, --warmup, --models, --threads,
// --config) and prints one table row per model on stdout; returns the exit code (0). Throws ConfigError
// for a bad configuration, std::runtime_error for an unreadable input or a frame the detector refuses.
int runDetectorBenchmark(const ArgParser& args);

}  // namespace bmp::detect_tools

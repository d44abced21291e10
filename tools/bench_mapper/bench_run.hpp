#pragma once
// bmp-bench-mapper's run: feeds keyframes through the mapper library (no LCM) and prints the integration
// time per keyframe (median, p95), the map's size and the peak resident memory (after each pass with
// --loops). Keyframes: every Nth frame of a TUM folder with its ground-truth pose (no masks), or of the
// synthetic scene (ground-truth masks).
#include "bmp/common/arg_parser.hpp"

namespace bmp::mapper {

void addBenchMapperOptions(ArgParser& args);
// Returns the exit code; throws ArgError, ConfigError or std::runtime_error.
int runBenchMapper(const ArgParser& args);

}  // namespace bmp::mapper

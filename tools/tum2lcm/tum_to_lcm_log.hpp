#pragma once
// tum2lcm's conversion: a TUM-format folder's frames, as bmp-capture would publish them, written into an LCM
// log file stamped with the recorded times.
#include "bmp/common/arg_parser.hpp"

namespace bmp::capture {

// Reads the options tum2lcm's main declares (--dataset, --out, --camera, --channel, --start, --end, --every,
// --verify, --max-diff); returns the exit code: 0 when at least one frame was written, else 1. Throws
// ArgError without --dataset or --out, std::runtime_error when the log cannot be written.
int convertTumToLcmLog(const ArgParser& args);

}  // namespace bmp::capture

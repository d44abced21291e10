#pragma once
// bmp-run's work once its arguments are parsed: prepare the run folder, start the processes and capture,
// supervise capture until the sequence ends, stop the others, evaluate the trajectory and summarise.
#include "bmp/common/arg_parser.hpp"

namespace bmp::launcher {

// args: bmp-run's options (see main.cpp). Returns the exit status: 0 when every process and the evaluation
// succeeded, 128 + the signal when the user stopped the run (130 for Ctrl-C), else 1. Throws (ArgError,
// ConfigError, std::runtime_error) for what stops a run before anything starts: a bad option, a bad
// configuration, an executable not built.
int runSession(const ArgParser& args);

}  // namespace bmp::launcher

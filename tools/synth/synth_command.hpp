#pragma once
// bmp-synth's command: its options, and the run they ask for (render the synthetic scene into a TUM-format
// folder, or time the rendering alone).
#include "bmp/common/arg_parser.hpp"

namespace bmp::synth {

void addSynthOptions(ArgParser& args);

// Loads the scene configuration (--config, else config/synthetic.yaml when it exists, else the built-in
// defaults) with the command line on top, then writes the folder or runs --bench; returns the exit code (0).
// Throws ArgError for a bad option value, ConfigError or std::runtime_error otherwise.
int runSynth(const ArgParser& args);

}  // namespace bmp::synth

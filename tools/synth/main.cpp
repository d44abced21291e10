// bmp-synth: renders the synthetic scene (textured room, moving objects, exact poses and masks) into a
// TUM-format folder that bmp-capture and the evaluation tools read like any recorded sequence.
#include "bmp/common/arg_parser.hpp"
#include "bmp/common/tool_main.hpp"
#include "synth_command.hpp"

int main(int argc, char** argv) {
  bmp::ArgParser args("bmp-synth", "Render the synthetic RGB-D scene into a TUM-format folder.");
  bmp::synth::addSynthOptions(args);
  return bmp::runTool(args, argc, argv, bmp::synth::runSynth);
}

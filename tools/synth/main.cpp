// bmp-synth: renders the synthetic scene (textured room, moving objects, exact poses and masks) into a
// TUM-format folder that bmp-capture and the evaluation tools read like any recorded sequence.
#include <exception>
#include <iostream>

#include "bmp/common/arg_parser.hpp"
#include "synth_command.hpp"

int main(int argc, char** argv) {
  bmp::ArgParser args("bmp-synth", "Render the synthetic RGB-D scene into a TUM-format folder.");
  bmp::synth::addSynthOptions(args);
  try {
    if (!args.parse(argc, argv)) {
      std::cout << args.help();
      return 0;
    }
    return bmp::synth::runSynth(args);
  } catch (const bmp::ArgError& e) {
    std::cerr << "bmp-synth: " << e.what() << "\n(see --help)\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "bmp-synth: " << e.what() << "\n";
    return 1;
  }
}

#pragma once
// The shared main of command-line tools (the processes have runProcess): --help, and every error as one line
// on stderr with a consistent exit status: 0 success, 1 failure while working, 2 bad arguments or
// configuration.
#include <functional>

#include "bmp/common/arg_parser.hpp"

namespace bmp {

int runTool(ArgParser& args, int argc, char** argv, const std::function<int(const ArgParser&)>& body);

}  // namespace bmp

#pragma once
// Output files checked before the work that fills them: a path that cannot be written, found only at the
// end of a long run, loses the run's results.
#include <string>

#include "bmp/common/arg_parser.hpp"

namespace bmp {

// When the option is given: throws ArgError naming it unless a file can be created at its path (the folder
// exists and is writable, and the path is not a folder). Nothing is created.
void checkOutputOption(const ArgParser& args, const std::string& option);

}  // namespace bmp

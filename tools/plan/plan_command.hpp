#pragma once
// bmp-plan's command: options, and planning on the grid from --map or --live with the path written out.
#include "bmp/common/arg_parser.hpp"

namespace bmp::plan {

void addPlanOptions(ArgParser& args);
// Exit 0 with a path, 1 without, 3 when no grid could be read, 4 when --out or --path-out could not be
// written; throws ArgError for bad arguments (an output folder that does not exist included).
int runPlan(const ArgParser& args);

}  // namespace bmp::plan

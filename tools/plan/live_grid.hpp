#pragma once
// The newest OCCUPANCY_GRID message as a PlanGrid (bmp-plan --live).
#include <string>

#include "plan/plan_grid.hpp"

namespace bmp::plan {

// Waits up to timeout_s for one message on channel; throws MapFileError when none arrives or it is
// inconsistent (cells not width x height, non-positive resolution).
PlanGrid receiveLiveGrid(const std::string& lcm_url, const std::string& channel, double timeout_s);

}  // namespace bmp::plan

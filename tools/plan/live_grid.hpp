#pragma once
// The newest OCCUPANCY_GRID message as a PlanGrid (bmp-plan --live).
#include <string>

#include <bmp/occupancy_grid_t.hpp>

#include "plan/plan_grid.hpp"

namespace bmp::plan {

// Waits up to timeout_s for a usable message on channel (an inconsistent one is reported, counted and
// waited past); throws MapFileError when none arrives.
PlanGrid receiveLiveGrid(const std::string& lcm_url, const std::string& channel, double timeout_s);
// Throws MapFileError for cells not width x height, a resolution not finite and positive, or an origin
// not finite or with a quaternion that is not a unit one.
PlanGrid planGridFromMessage(const occupancy_grid_t& m);

}  // namespace bmp::plan

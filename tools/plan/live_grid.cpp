#include "plan/live_grid.hpp"

#include <bmp/occupancy_grid_t.hpp>

#include <cmath>
#include <optional>
#include <sstream>

#include "bmp/common/timing.hpp"
#include "bmp/lcm/conversions.hpp"
#include "bmp/lcm/lcm_node.hpp"

namespace bmp::plan {

PlanGrid planGridFromMessage(const occupancy_grid_t& m) {
  if (!(m.resolution > 0) || !std::isfinite(m.resolution) || m.width <= 0 || m.height <= 0 ||
      static_cast<int64_t>(m.width) * m.height != m.num_cells)
    throw MapFileError("OCCUPANCY_GRID message: inconsistent size or resolution");
  if (const std::string why = checkPoseMessage(m.origin); !why.empty())
    throw MapFileError("OCCUPANCY_GRID message: origin: " + why);
  PlanGrid grid;
  grid.resolution = m.resolution;
  grid.width = m.width;
  grid.height = m.height;
  grid.cells = m.cells;
  // The origin pose's rotation holds the plane's axes: its corner in plane coordinates is R^T t.
  const SE3 T_world_origin = fromMsg(m.origin);
  grid.origin = (T_world_origin.linear().transpose() * T_world_origin.translation()).head<2>();
  return grid;
}

PlanGrid receiveLiveGrid(const std::string& lcm_url, const std::string& channel, double timeout_s) {
  LcmNode node(resolveLcmUrl(lcm_url));
  std::optional<PlanGrid> latest;
  // Checked as it arrives: an inconsistent grid (another publisher's) is reported and counted by the node,
  // and the wait goes on for a good one.
  node.subscribe<occupancy_grid_t>(
      channel, [&](const occupancy_grid_t& m, const ReceivedInfo&) { latest = planGridFromMessage(m); });
  Stopwatch watch;
  while (!latest && watch.elapsedMs() < timeout_s * 1000.0) node.handle(100);
  if (!latest) {
    std::ostringstream why;
    why << "no " << channel << " message within " << timeout_s << " s";
    if (node.malformedCount() > 0) why << " that could be used (" << node.malformedCount() << " refused)";
    why << " (is bmp-mapper running on this LCM URL?)";
    throw MapFileError(why.str());
  }
  return *latest;
}

}  // namespace bmp::plan

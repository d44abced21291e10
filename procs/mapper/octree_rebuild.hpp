#pragma once
// Octree rebuilds off the mapper's thread. A rebuild casts every stored keyframe's rays again (seconds at a
// few hundred keyframes: 6.3 s at Bonn's 308 with bmp-bench-mapper). Done in the thread that reads LCM, the
// keyframes sent meanwhile overflowed the socket's buffer and were lost, and with more keyframes than one
// interval's worth of rebuild the mapper did nothing else. So a rebuild casts a snapshot of the rays into a
// new octree on a thread of its own; the mapper goes on casting into the one it has and swaps when done.
#include <atomic>
#include <future>
#include <memory>
#include <vector>

#include <Eigen/Geometry>

#include "mapper/mapper_settings.hpp"
#include "mapper/occupancy_map.hpp"

namespace bmp::mapper {

// One cast: rays from origin to each point (both in the camera frame), placed by T_world_cam, counted
// weight times (OccupancyMap::insertScan).
struct OctreeCast {
  Eigen::Isometry3f T_world_cam = Eigen::Isometry3f::Identity();
  Eigen::Vector3f origin = Eigen::Vector3f::Zero();
  std::vector<Eigen::Vector3f> points;
  int weight = 1;
};

void castInto(OccupancyMap& octree, const OctreeCast& cast);

// A new octree from casts, in their order; stops early (and returns nullptr) once cancel is set.
std::unique_ptr<OccupancyMap> buildOctree(const OctomapSettings& settings,
                                          const std::vector<OctreeCast>& casts,
                                          const std::atomic<bool>& cancel);

// A rebuild running on its own thread. Destroying it cancels it and waits for the thread.
class BackgroundRebuild {
 public:
  BackgroundRebuild(const OctomapSettings& settings, std::vector<OctreeCast> casts);
  ~BackgroundRebuild();
  BackgroundRebuild(const BackgroundRebuild&) = delete;
  BackgroundRebuild& operator=(const BackgroundRebuild&) = delete;

  bool done() const;
  // The new octree, waiting for it if need be. Once only.
  std::unique_ptr<OccupancyMap> take();

 private:
  std::atomic<bool> cancel_{false};
  const std::vector<OctreeCast> casts_;
  std::future<std::unique_ptr<OccupancyMap>> result_;  // last: started once the casts are in place
};

}  // namespace bmp::mapper

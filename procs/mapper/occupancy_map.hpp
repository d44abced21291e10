#pragma once
// The OctoMap occupancy octree of the static map: points inserted with ray casting from the camera, so free
// space is carved and a ghost left by a mover is cleared once the space behind it is seen again. OctoMap's
// headers stay in the .cpp; users who want the tree itself include <octomap/OcTree.h>.
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "mapper/mapper_settings.hpp"
#include "mapper/occupancy_grid.hpp"

namespace octomap {
class OcTree;
}

namespace bmp::mapper {

enum class Occupancy { kUnknown, kFree, kOccupied };

class OccupancyMap {
 public:
  explicit OccupancyMap(const OctomapSettings& settings);
  ~OccupancyMap();
  OccupancyMap(const OccupancyMap&) = delete;
  OccupancyMap& operator=(const OccupancyMap&) = delete;
  OccupancyMap(OccupancyMap&&) noexcept;
  OccupancyMap& operator=(OccupancyMap&&) noexcept;

  // One scan: every point is a hit, every voxel on the way from origin a miss; rays are cut at max_range.
  // weight: the scan counts as cast this many times (each of its cells updated once by weight x the hit or
  // miss log-odds, which the clamping makes the same as casting it again and again).
  void insertScan(const std::vector<Eigen::Vector3f>& points_world, const Eigen::Vector3d& origin_world,
                  int weight = 1);
  // How many casts take a leaf from one clamping bound to the other: more than this are forgotten.
  int saturatingCasts() const;
  Occupancy query(const Eigen::Vector3d& p_world) const;
  // The leaf's occupancy probability, or -1 where nothing is known.
  double probability(const Eigen::Vector3d& p_world) const;

  // The grid: leaves whose height span meets [height_min, height_max] projected along the plane's up;
  // a cell is occupied if any such leaf is, free if one is free and none occupied, unknown otherwise. Then
  // unknown cells within camera_free_radius_m of a camera centre (world) become free; the grid spans them.
  OccupancyGrid2D project(const GridSettings& settings,
                          const std::vector<Eigen::Vector3d>& camera_centres = {}) const;

  // OcTree::writeBinaryData (the octomap_t message's payload) and the whole .bt file (writeBinaryConst):
  // both the maximum-likelihood tree, leaving this one's probabilities untouched.
  std::string binaryData() const;
  std::string binaryFile() const;

  double resolution() const;
  std::size_t nodeCount() const;
  std::size_t memoryBytes() const;
  const octomap::OcTree& tree() const { return *tree_; }

 private:
  OctomapSettings settings_;
  std::unique_ptr<octomap::OcTree> tree_;
};

}  // namespace bmp::mapper

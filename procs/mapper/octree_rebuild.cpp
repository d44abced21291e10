#include "mapper/octree_rebuild.hpp"

#include <chrono>

namespace bmp::mapper {

void castInto(OccupancyMap& octree, const OctreeCast& cast) {
  std::vector<Eigen::Vector3f> world;
  world.reserve(cast.points.size());
  for (const auto& p : cast.points) world.push_back(cast.T_world_cam * p);
  octree.insertScan(world, (cast.T_world_cam * cast.origin).cast<double>(), cast.weight);
}

std::unique_ptr<OccupancyMap> buildOctree(const OctomapSettings& settings,
                                          const std::vector<OctreeCast>& casts,
                                          const std::atomic<bool>& cancel) {
  auto octree = std::make_unique<OccupancyMap>(settings);
  for (const auto& cast : casts) {
    if (cancel.load(std::memory_order_relaxed)) return nullptr;
    castInto(*octree, cast);
  }
  return octree;
}

BackgroundRebuild::BackgroundRebuild(const OctomapSettings& settings, std::vector<OctreeCast> casts)
    : casts_(std::move(casts)), result_(std::async(std::launch::async, [this, settings] {
        return buildOctree(settings, casts_, cancel_);
      })) {}

BackgroundRebuild::~BackgroundRebuild() {
  cancel_ = true;
  if (result_.valid()) result_.wait();
}

bool BackgroundRebuild::done() const {
  return result_.wait_for(std::chrono::seconds(0)) == std::future_status::ready;
}

std::unique_ptr<OccupancyMap> BackgroundRebuild::take() {
  return result_.get();
}

}  // namespace bmp::mapper

#include "mapper/occupancy_map.hpp"

#include <octomap/OcTree.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace bmp::mapper {

namespace {

std::unique_ptr<octomap::OcTree> makeTree(const OctomapSettings& s) {
  auto tree = std::make_unique<octomap::OcTree>(s.resolution_m);
  tree->setProbHit(s.prob_hit);
  tree->setProbMiss(s.prob_miss);
  tree->setClampingThresMin(s.clamp_min);
  tree->setClampingThresMax(s.clamp_max);
  tree->setOccupancyThres(s.occupied_threshold);
  return tree;
}

// A leaf of the height band, in plane coordinates.
struct BandLeaf {
  Eigen::Vector2d centre;
  double half_extent;
  bool occupied;
};

std::vector<BandLeaf> bandLeaves(const octomap::OcTree& tree, const GridSettings& s, const PlaneFrame& f) {
  // Half the extent of a unit cube seen along each plane axis (1/2 when the axis is a world axis).
  const auto spread = [](const Eigen::Vector3d& a) { return 0.5 * a.cwiseAbs().sum(); };
  const double up_spread = spread(f.up), x_spread = spread(f.x_axis), y_spread = spread(f.y_axis);
  std::vector<BandLeaf> out;
  for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it) {
    const Eigen::Vector3d c(it.getX(), it.getY(), it.getZ());
    const double size = it.getSize();
    const double h = f.height(c);
    const double eps = 1e-6;  // a leaf that merely touches the band's edge is outside it
    if (h + size * up_spread <= s.height_min_m + eps || h - size * up_spread >= s.height_max_m - eps)
      continue;
    out.push_back({f.planar(c), size * std::max(x_spread, y_spread), tree.isNodeOccupied(*it)});
  }
  return out;
}

void rasterise(const BandLeaf& leaf, OccupancyGrid2D& grid) {
  const double r = grid.resolution;
  const Eigen::Vector2d lo = (leaf.centre.array() - leaf.half_extent - grid.origin.array()) / r - 0.5;
  const Eigen::Vector2d hi = (leaf.centre.array() + leaf.half_extent - grid.origin.array()) / r - 0.5;
  const int c0 = std::max(0, static_cast<int>(std::ceil(lo.x() - 1e-6)));
  const int r0 = std::max(0, static_cast<int>(std::ceil(lo.y() - 1e-6)));
  const int c1 = std::min(grid.width - 1, static_cast<int>(std::floor(hi.x() + 1e-6)));
  const int r1 = std::min(grid.height - 1, static_cast<int>(std::floor(hi.y() + 1e-6)));
  for (int row = r0; row <= r1; ++row) {
    for (int col = c0; col <= c1; ++col) {
      int8_t& cell = grid.cells[static_cast<std::size_t>(row) * grid.width + col];
      if (leaf.occupied)
        cell = kCellOccupied;
      else if (cell == kCellUnknown)
        cell = kCellFree;
    }
  }
}

// Unknown cells whose centre lies within the leaf's half extent of its centre become free.
void rasteriseDisc(const BandLeaf& disc, OccupancyGrid2D& grid) {
  const double r = grid.resolution;
  const int c0 =
      std::max(0, static_cast<int>(std::floor((disc.centre.x() - disc.half_extent - grid.origin.x()) / r)));
  const int r0 =
      std::max(0, static_cast<int>(std::floor((disc.centre.y() - disc.half_extent - grid.origin.y()) / r)));
  const int c1 =
      std::min(grid.width - 1,
               static_cast<int>(std::floor((disc.centre.x() + disc.half_extent - grid.origin.x()) / r)));
  const int r1 =
      std::min(grid.height - 1,
               static_cast<int>(std::floor((disc.centre.y() + disc.half_extent - grid.origin.y()) / r)));
  for (int row = r0; row <= r1; ++row)
    for (int col = c0; col <= c1; ++col) {
      const Eigen::Vector2d centre = grid.origin + r * Eigen::Vector2d(col + 0.5, row + 0.5);
      int8_t& cell = grid.cells[static_cast<std::size_t>(row) * grid.width + col];
      if (cell == kCellUnknown && (centre - disc.centre).norm() <= disc.half_extent) cell = kCellFree;
    }
}

}  // namespace

OccupancyMap::OccupancyMap(const OctomapSettings& settings)
    : settings_(settings), tree_(makeTree(settings)) {}
OccupancyMap::~OccupancyMap() = default;
OccupancyMap::OccupancyMap(OccupancyMap&&) noexcept = default;
OccupancyMap& OccupancyMap::operator=(OccupancyMap&&) noexcept = default;

void OccupancyMap::insertScan(const std::vector<Eigen::Vector3f>& points_world, const Eigen::Vector3d& origin,
                              int weight) {
  octomap::Pointcloud scan;
  scan.reserve(points_world.size());
  for (const auto& p : points_world) scan.push_back(p.x(), p.y(), p.z());
  const octomap::point3d from(static_cast<float>(origin.x()), static_cast<float>(origin.y()),
                              static_cast<float>(origin.z()));
  // discretize: endpoints in one voxel are cast once, which keeps integration fast.
  if (weight <= 1) return tree_->insertPointCloud(scan, from, settings_.max_range_m, false, true);
  octomap::KeySet free_cells, occupied_cells;
  tree_->computeDiscreteUpdate(scan, from, free_cells, occupied_cells, settings_.max_range_m);
  // As insertPointCloud: a cell both passed through and hit is a hit.
  const float miss = static_cast<float>(weight) * tree_->getProbMissLog();
  const float hit = static_cast<float>(weight) * tree_->getProbHitLog();
  for (const auto& key : free_cells)
    if (occupied_cells.find(key) == occupied_cells.end()) tree_->updateNode(key, miss);
  for (const auto& key : occupied_cells) tree_->updateNode(key, hit);
}

int OccupancyMap::saturatingCasts() const {
  const double span = tree_->getClampingThresMaxLog() - tree_->getClampingThresMinLog();
  const double step = std::min(std::abs(tree_->getProbHitLog()), std::abs(tree_->getProbMissLog()));
  return step > 0 ? static_cast<int>(std::ceil(span / step)) : 1;
}

Occupancy OccupancyMap::query(const Eigen::Vector3d& p) const {
  const octomap::OcTreeNode* node = tree_->search(p.x(), p.y(), p.z());
  if (node == nullptr) return Occupancy::kUnknown;
  return tree_->isNodeOccupied(node) ? Occupancy::kOccupied : Occupancy::kFree;
}

double OccupancyMap::probability(const Eigen::Vector3d& p) const {
  const octomap::OcTreeNode* node = tree_->search(p.x(), p.y(), p.z());
  return node == nullptr ? -1.0 : node->getOccupancy();
}

OccupancyGrid2D OccupancyMap::project(const GridSettings& s,
                                      const std::vector<Eigen::Vector3d>& camera_centres) const {
  OccupancyGrid2D grid;
  grid.resolution = s.resolution_m;
  grid.frame = PlaneFrame::fromUp(s.up, s.axes_from);
  std::vector<BandLeaf> leaves = bandLeaves(*tree_, s, grid.frame);
  // A camera's floor disc as a free leaf, rasterised after the octree's: it fills only unknown cells.
  const std::size_t octree_leaves = leaves.size();
  if (s.camera_free_radius_m > 0)
    for (const auto& c : camera_centres)
      leaves.push_back({grid.frame.planar(c), s.camera_free_radius_m, false});
  if (leaves.empty()) {  // nothing in the band yet: one unknown cell, still an image map_server can load
    grid.width = grid.height = 1;
    grid.cells.assign(1, kCellUnknown);
    return grid;
  }
  Eigen::Vector2d lo = leaves[0].centre, hi = lo;
  for (const auto& l : leaves) {
    const Eigen::Vector2d half = Eigen::Vector2d::Constant(l.half_extent);
    lo = lo.cwiseMin(l.centre - half);
    hi = hi.cwiseMax(l.centre + half);
  }
  // Cell edges on multiples of the resolution, where the octree's voxel edges are.
  grid.origin = (lo / s.resolution_m).array().floor() * s.resolution_m;
  grid.width = std::max(1, static_cast<int>(std::ceil((hi.x() - grid.origin.x()) / s.resolution_m - 1e-6)));
  grid.height = std::max(1, static_cast<int>(std::ceil((hi.y() - grid.origin.y()) / s.resolution_m - 1e-6)));
  grid.cells.assign(static_cast<std::size_t>(grid.width) * grid.height, kCellUnknown);
  for (std::size_t i = 0; i < octree_leaves; ++i) rasterise(leaves[i], grid);
  for (std::size_t i = octree_leaves; i < leaves.size(); ++i) rasteriseDisc(leaves[i], grid);
  return grid;
}

// OcTree::writeBinaryData and writeBinaryConst print "Writing N nodes ... done." from the installed library
// (built without NDEBUG); the node recursion they wrap is silent, so the mapper's log stays its own.
std::string OccupancyMap::binaryData() const {
  std::ostringstream out;
  if (tree_->getRoot() != nullptr) tree_->writeBinaryNode(out, tree_->getRoot());
  return out.str();
}

std::string OccupancyMap::binaryFile() const {
  // The header writeBinaryConst writes (AbstractOccupancyOcTree::binaryFileHeader and its fields), which
  // OcTree::readBinary, octovis and every OctoMap reader expect.
  std::ostringstream out;
  out << "# Octomap OcTree binary file\n"
      << "# (feel free to add / change comments, but leave the first line as it is!)\n#\n"
      << "id " << tree_->getTreeType() << "\nsize " << tree_->size() << "\nres " << tree_->getResolution()
      << "\ndata\n";
  out << binaryData();
  return out.str();
}

double OccupancyMap::resolution() const {
  return tree_->getResolution();
}
std::size_t OccupancyMap::nodeCount() const {
  return tree_->size();
}
std::size_t OccupancyMap::memoryBytes() const {
  return tree_->memoryUsage();
}

}  // namespace bmp::mapper

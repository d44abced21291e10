#include "mapper/voxel_filter.hpp"

#include <pcl/filters/voxel_grid.h>
#include <pcl/point_types.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "mapper/pcl_points.hpp"

namespace bmp::mapper {

namespace {

// PCL refuses (and passes through unfiltered) grids with more voxels than an int32 can index.
constexpr double kMaxVoxels = 1.0e9;

PointList filterOnce(const PointList& in, float leaf) {
  const pcl::PointCloud<pcl::PointXYZRGB>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZRGB>(toPcl(in)));
  pcl::VoxelGrid<pcl::PointXYZRGB> grid;
  grid.setInputCloud(cloud);
  grid.setLeafSize(leaf, leaf, leaf);
  pcl::PointCloud<pcl::PointXYZRGB> filtered;
  grid.filter(filtered);
  return fromPcl(filtered);
}

void filterInto(const PointList& in, float leaf, PointList& out) {
  if (in.empty()) return;
  Eigen::Vector3f lo = in[0].position(), hi = lo;
  for (const auto& p : in) {
    lo = lo.cwiseMin(p.position());
    hi = hi.cwiseMax(p.position());
  }
  const Eigen::Vector3f cells = ((hi - lo) / leaf).array() + 1.0f;
  if (static_cast<double>(cells.x()) * cells.y() * cells.z() < kMaxVoxels) {
    const PointList part = filterOnce(in, leaf);
    out.insert(out.end(), part.begin(), part.end());
    return;
  }
  // Cut the longest side on a voxel boundary: each voxel stays whole in one half.
  int axis = 0;
  (hi - lo).maxCoeff(&axis);
  const float cut = std::floor((lo[axis] + hi[axis]) * 0.5f / leaf) * leaf;
  PointList below, above;
  for (const auto& p : in) (p.position()[axis] < cut ? below : above).push_back(p);
  if (below.empty() ||
      above.empty()) {  // cannot split further (degenerate spread): PCL copes or passes through
    const PointList part = filterOnce(in, leaf);
    out.insert(out.end(), part.begin(), part.end());
    return;
  }
  filterInto(below, leaf, out);
  filterInto(above, leaf, out);
}

}  // namespace

PointList voxelFilter(const PointList& in, double leaf) {
  PointList out;
  out.reserve(in.size() / 2);
  filterInto(in, static_cast<float>(leaf), out);
  return out;
}

}  // namespace bmp::mapper

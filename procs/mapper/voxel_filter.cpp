#include "mapper/voxel_filter.hpp"

#include <pcl/filters/voxel_grid.h>
#include <pcl/point_types.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace bmp::mapper {

namespace {

// PCL refuses (and passes through unfiltered) grids with more voxels than an int32 can index.
constexpr double kMaxVoxels = 1.0e9;

PointList filterOnce(const PointList& in, float leaf) {
  pcl::PointCloud<pcl::PointXYZRGB>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZRGB>);
  cloud->resize(in.size());
  for (std::size_t i = 0; i < in.size(); ++i) {
    pcl::PointXYZRGB& q = (*cloud)[i];
    q.x = in[i].x;
    q.y = in[i].y;
    q.z = in[i].z;
    q.r = in[i].r;
    q.g = in[i].g;
    q.b = in[i].b;
  }
  pcl::VoxelGrid<pcl::PointXYZRGB> grid;
  grid.setInputCloud(cloud);
  grid.setLeafSize(leaf, leaf, leaf);
  pcl::PointCloud<pcl::PointXYZRGB> filtered;
  grid.filter(filtered);
  PointList out(filtered.size());
  for (std::size_t i = 0; i < filtered.size(); ++i) {
    const pcl::PointXYZRGB& q = filtered[i];
    out[i] = ColoredPoint{q.x, q.y, q.z, q.r, q.g, q.b};
  }
  return out;
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

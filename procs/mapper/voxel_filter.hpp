#pragma once
// Voxel-grid down-sampling (PCL's VoxelGrid: one point per occupied voxel, position and colour averaged).
#include "mapper/point_types.hpp"

namespace bmp::mapper {

// Voxels of `leaf` metres aligned to multiples of leaf. Any extent works: a cloud whose voxel count would
// overflow PCL's 32-bit index is filtered in slabs cut on voxel boundaries.
PointList voxelFilter(const PointList& in, double leaf);

}  // namespace bmp::mapper

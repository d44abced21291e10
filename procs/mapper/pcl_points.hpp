#pragma once
// Conversion between the mapper's point list and PCL's coloured cloud, in one place. Included only by the
// .cpp files that call PCL (voxel filter, PCD writer), so PCL stays out of every other header.
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include "mapper/point_types.hpp"

namespace bmp::mapper {

pcl::PointCloud<pcl::PointXYZRGB> toPcl(const PointList& in);
PointList fromPcl(const pcl::PointCloud<pcl::PointXYZRGB>& in);

}  // namespace bmp::mapper

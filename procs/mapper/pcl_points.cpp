#include "mapper/pcl_points.hpp"

namespace bmp::mapper {

pcl::PointCloud<pcl::PointXYZRGB> toPcl(const PointList& in) {
  pcl::PointCloud<pcl::PointXYZRGB> out;
  out.resize(in.size());
  for (std::size_t i = 0; i < in.size(); ++i) {
    pcl::PointXYZRGB& q = out[i];
    q.x = in[i].x;
    q.y = in[i].y;
    q.z = in[i].z;
    q.r = in[i].r;
    q.g = in[i].g;
    q.b = in[i].b;
  }
  return out;
}

PointList fromPcl(const pcl::PointCloud<pcl::PointXYZRGB>& in) {
  PointList out(in.size());
  for (std::size_t i = 0; i < in.size(); ++i) {
    const pcl::PointXYZRGB& q = in[i];
    out[i] = ColoredPoint{q.x, q.y, q.z, q.r, q.g, q.b};
  }
  return out;
}

}  // namespace bmp::mapper

#include "mapper/cloud_files.hpp"

#include <pcl/conversions.h>
#include <pcl/io/pcd_io.h>
#include <pcl/point_types.h>

#include <cstring>

#include "mapper/pcl_points.hpp"

namespace bmp::mapper {

std::string encodePcd(const PointList& cloud) {
  pcl::PCLPointCloud2 blob;
  pcl::toPCLPointCloud2(toPcl(cloud), blob);
  // PCL's binary PCD is its header followed by the blob's bytes (padding fields declared in the header);
  // built in memory so the file can be replaced atomically.
  pcl::PCDWriter writer;
  std::string out =
      writer.generateHeaderBinary(blob, Eigen::Vector4f::Zero(), Eigen::Quaternionf::Identity());
  out += "DATA binary\n";
  out.append(reinterpret_cast<const char*>(blob.data.data()), blob.data.size());
  return out;
}

std::string encodePly(const PointList& cloud) {
  std::string out =
      "ply\nformat binary_little_endian 1.0\ncomment bmp-mapper static map, world frame, metres\n";
  out += "element vertex " + std::to_string(cloud.size()) + "\n";
  out += "property float x\nproperty float y\nproperty float z\n";
  out += "property uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n";
  const std::size_t record = 3 * sizeof(float) + 3;
  const std::size_t start = out.size();
  out.resize(start + record * cloud.size());
  char* at = &out[start];
  for (const auto& p : cloud) {  // x86 is little-endian, as the header says
    const float xyz[3] = {p.x, p.y, p.z};
    std::memcpy(at, xyz, sizeof(xyz));
    at[12] = static_cast<char>(p.r);
    at[13] = static_cast<char>(p.g);
    at[14] = static_cast<char>(p.b);
    at += record;
  }
  return out;
}

}  // namespace bmp::mapper

#pragma once
// The mapper's own point type: PCL stays inside the few .cpp files that filter and write clouds, so headers
// that other files include compile fast.
#include <cstdint>
#include <vector>

#include <Eigen/Core>

namespace bmp::mapper {

struct ColoredPoint {
  float x = 0, y = 0, z = 0;  // metres, in the frame the container says
  uint8_t r = 0, g = 0, b = 0;
  Eigen::Vector3f position() const { return {x, y, z}; }
};

using PointList = std::vector<ColoredPoint>;

}  // namespace bmp::mapper

#pragma once
// A coloured cloud as the bytes of a file: binary PCD (PCL's format, written by PCL) and binary PLY.
#include <string>

#include "mapper/point_types.hpp"

namespace bmp::mapper {

std::string encodePcd(const PointList& cloud);
std::string encodePly(const PointList& cloud);

}  // namespace bmp::mapper

#include "bmp/common/number_format.hpp"

#include <cmath>
#include <cstdio>

namespace bmp {

std::string formatFixed(double value, int digits, const std::string& if_not_finite) {
  if (!std::isfinite(value)) return if_not_finite;
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "%.*f", digits, value);
  return buffer;
}

}  // namespace bmp

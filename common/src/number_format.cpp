#include "bmp/common/number_format.hpp"

#include <cmath>
#include <cstdio>

namespace bmp {

std::string formatFixed(double value, int digits, const std::string& if_not_finite) {
  if (!std::isfinite(value)) return if_not_finite;
  // Sized by the number itself: 1e100 has 101 digits before the point (a fixed buffer cut it short, and
  // it read back as another number).
  const int length = std::snprintf(nullptr, 0, "%.*f", digits, value);
  std::string text(static_cast<std::size_t>(length) + 1, '\0');
  std::snprintf(text.data(), text.size(), "%.*f", digits, value);
  text.resize(static_cast<std::size_t>(length));
  return text;
}

}  // namespace bmp

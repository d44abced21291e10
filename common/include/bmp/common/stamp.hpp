#pragma once
// Stamps: seconds (TUM files, the algorithms) and LCM's integer microseconds (utime). One rounding rule for
// both ways.
#include <cmath>
#include <cstdint>

namespace bmp {

inline int64_t secondsToUtime(double seconds) {
  return static_cast<int64_t>(std::llround(seconds * 1e6));
}

inline double utimeToSeconds(int64_t utime) {
  return static_cast<double>(utime) * 1e-6;
}

}  // namespace bmp

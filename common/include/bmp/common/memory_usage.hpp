#pragma once
// This process's resident memory, from /proc (Linux).
#include <cstddef>

namespace bmp {

std::size_t residentBytes();      // now (VmRSS); 0 when unknown
std::size_t peakResidentBytes();  // the high-water mark (VmHWM); 0 when unknown

}  // namespace bmp

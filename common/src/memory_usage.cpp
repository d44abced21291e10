#include "bmp/common/memory_usage.hpp"

#include <fstream>
#include <string>

namespace bmp {

namespace {
std::size_t statusField(const std::string& key) {
  std::ifstream in("/proc/self/status");
  std::string name;
  std::size_t kib = 0;
  while (in >> name) {
    if (name == key && in >> kib) return kib * 1024;
    in.ignore(1 << 12, '\n');
  }
  return 0;
}
}  // namespace

std::size_t residentBytes() {
  return statusField("VmRSS:");
}
std::size_t peakResidentBytes() {
  return statusField("VmHWM:");
}

}  // namespace bmp

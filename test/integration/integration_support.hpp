#pragma once
// Helpers for tests that run the real processes over a real udpm:// LCM URL.
#include <unistd.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "shared_data.hpp"

namespace bmp::test {

// A multicast URL on a port unique to this test process and slot, so parallel tests never hear each other.
inline std::string uniqueLcmUrl(int slot) {
  const int port = 20000 + static_cast<int>(::getpid() % 2000) * 8 + slot;
  return "udpm://239.255.76.67:" + std::to_string(port) + "?ttl=0&recv_buf_size=4194304";
}

struct ReportLine {
  long long seq = 0, utime = 0, depth_utime = 0, color_bytes = 0, depth_bytes = 0;
  int decoded = 0;
};

inline std::vector<ReportLine> readReport(const std::string& path) {
  std::vector<ReportLine> lines;
  std::ifstream in(path);
  ReportLine r;
  while (in >> r.seq >> r.utime >> r.depth_utime >> r.color_bytes >> r.depth_bytes >> r.decoded)
    lines.push_back(r);
  return lines;
}

inline std::string readText(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace bmp::test

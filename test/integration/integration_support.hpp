#pragma once
// Helpers for tests that run the real processes over a real udpm:// LCM URL.
#include <unistd.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "lcm_url.hpp"
#include "shared_data.hpp"

namespace bmp::test {

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

#pragma once
// Text for the JSON the tools write (bmp-eval's report, bmp-detect's detections): one quoting rule for all.
#include <string>

namespace bmp {

// s as a JSON string literal, quotes included: '"' and '\' escaped, newline and tab as \n and \t, other
// control characters as \u00XX; other bytes (UTF-8 included) kept as they are.
std::string jsonString(const std::string& s);

}  // namespace bmp

#pragma once
// Numbers as text for reports (evaluation, run summary): fixed digits, and a word of the caller's choice
// where there is no number (NaN, infinity), e.g. "n/a" in text or "null" in JSON.
#include <string>

namespace bmp {

std::string formatFixed(double value, int digits, const std::string& if_not_finite);

}  // namespace bmp

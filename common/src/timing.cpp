#include "bmp/common/timing.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <numeric>
#include <sstream>

namespace bmp {

double percentileOf(std::vector<double> values, double pct) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  const double rank = std::clamp(pct, 0.0, 100.0) / 100.0 * static_cast<double>(values.size() - 1);
  const auto lo = static_cast<std::size_t>(std::floor(rank));
  const auto hi = static_cast<std::size_t>(std::ceil(rank));
  const double frac = rank - static_cast<double>(lo);
  // Selection, not a sort: asked of every sample so far in status lines, and a long run has many.
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(lo), values.end());
  const double at_lo = values[lo];
  const double at_hi =
      hi == lo ? at_lo
               : *std::min_element(values.begin() + static_cast<std::ptrdiff_t>(lo) + 1, values.end());
  return at_lo + (at_hi - at_lo) * frac;
}

double TimingStats::percentile(double pct) const {
  return percentileOf(samples_, pct);
}

double TimingStats::mean() const {
  if (samples_.empty()) return std::numeric_limits<double>::quiet_NaN();
  return std::accumulate(samples_.begin(), samples_.end(), 0.0) / static_cast<double>(samples_.size());
}

double TimingStats::max() const {
  if (samples_.empty()) return std::numeric_limits<double>::quiet_NaN();
  return *std::max_element(samples_.begin(), samples_.end());
}

std::string TimingStats::summary() const {
  std::ostringstream out;
  out << std::fixed << std::setprecision(2) << "median " << median() << " ms, p95 " << p95() << " ms, n "
      << count();
  return out.str();
}

}  // namespace bmp

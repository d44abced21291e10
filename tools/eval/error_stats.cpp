#include "eval/error_stats.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace bmp::eval {

ErrorStats computeStats(const std::vector<double>& values) {
  ErrorStats s;
  s.count = values.size();
  if (values.empty()) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    s.rmse = s.mean = s.median = s.std = s.min = s.max = nan;
    return s;
  }
  const double n = static_cast<double>(values.size());
  double sum = 0.0;
  double sum_sq = 0.0;
  for (double v : values) {
    sum += v;
    sum_sq += v * v;
  }
  s.mean = sum / n;
  s.rmse = std::sqrt(sum_sq / n);
  // Two-pass variance: the one-pass formula cancels badly when errors are nearly constant.
  double var = 0.0;
  for (double v : values) var += (v - s.mean) * (v - s.mean);
  s.std = std::sqrt(var / n);
  std::vector<double> sorted = values;
  std::sort(sorted.begin(), sorted.end());
  const std::size_t mid = sorted.size() / 2;
  s.median = sorted.size() % 2 == 1 ? sorted[mid] : 0.5 * (sorted[mid - 1] + sorted[mid]);
  s.min = sorted.front();
  s.max = sorted.back();
  return s;
}

ErrorStats scaled(const ErrorStats& stats, double factor) {
  ErrorStats s = stats;
  s.rmse *= factor;
  s.mean *= factor;
  s.median *= factor;
  s.std *= factor;
  s.min *= factor;
  s.max *= factor;
  return s;
}

}  // namespace bmp::eval

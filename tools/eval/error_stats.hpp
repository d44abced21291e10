#pragma once
// Summary statistics of an error list, defined as numpy computes them in the TUM scripts.
#include <cstddef>
#include <vector>

namespace bmp::eval {

struct ErrorStats {
  std::size_t count = 0;
  // All NaN when count == 0.
  double rmse = 0.0;
  double mean = 0.0;
  double median = 0.0;  // mean of the two middle values for an even count (numpy.median)
  double std = 0.0;     // population standard deviation (numpy.std, ddof=0)
  double min = 0.0;
  double max = 0.0;
};

ErrorStats computeStats(const std::vector<double>& values);
// Every field multiplied by factor (count unchanged), e.g. radians to degrees.
ErrorStats scaled(const ErrorStats& stats, double factor);

}  // namespace bmp::eval

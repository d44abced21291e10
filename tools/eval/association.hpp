#pragma once
// Stamp association of evaluate_ate.py (associate.py): every pair closer than max_difference is a
// candidate; candidates are taken greedily by (difference, first stamp, second stamp), each stamp at most
// once; the result is ordered by the first stamp.
#include <cstddef>
#include <vector>

namespace bmp::eval {

struct Match {
  std::size_t first = 0;    // index into the first (ground-truth) stamps
  std::size_t second = 0;   // index into the second (estimated) stamps
  double difference = 0.0;  // |first - (second + offset)|, seconds
};

// Both stamp lists must be sorted ascending and free of repeats.
std::vector<Match> associate(const std::vector<double>& first, const std::vector<double>& second,
                             double offset, double max_difference);

}  // namespace bmp::eval

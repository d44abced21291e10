#include "eval/association.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace bmp::eval {

std::vector<Match> associate(const std::vector<double>& first, const std::vector<double>& second,
                             double offset, double max_difference) {
  // Candidate search by binary search instead of the script's all-pairs loop; the margin makes sure no
  // pair is lost to rounding, and the exact test below is the script's.
  const double margin = max_difference + 1e-3;
  std::vector<Match> candidates;
  for (std::size_t a = 0; a < first.size(); ++a) {
    const double target = first[a] - offset;
    auto it = std::lower_bound(second.begin(), second.end(), target - margin);
    for (; it != second.end() && *it <= target + margin; ++it) {
      const std::size_t b = static_cast<std::size_t>(it - second.begin());
      const double diff = std::abs(first[a] - (second[b] + offset));
      if (diff < max_difference) candidates.push_back({a, b, diff});
    }
  }
  // Sorted indices order like the stamps themselves, so (difference, a, b) is the script's tuple order.
  std::sort(candidates.begin(), candidates.end(), [](const Match& x, const Match& y) {
    return std::tie(x.difference, x.first, x.second) < std::tie(y.difference, y.first, y.second);
  });
  std::vector<bool> used_first(first.size(), false);
  std::vector<bool> used_second(second.size(), false);
  std::vector<Match> matches;
  for (const Match& m : candidates) {
    if (used_first[m.first] || used_second[m.second]) continue;
    used_first[m.first] = true;
    used_second[m.second] = true;
    matches.push_back(m);
  }
  std::sort(matches.begin(), matches.end(), [](const Match& x, const Match& y) { return x.first < y.first; });
  return matches;
}

}  // namespace bmp::eval

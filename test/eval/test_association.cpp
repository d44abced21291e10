#include <gtest/gtest.h>

#include "eval/association.hpp"

namespace bmp::eval {

namespace {
std::vector<std::pair<double, double>> matchedStamps(const std::vector<double>& first,
                                                     const std::vector<double>& second, double offset,
                                                     double max_difference) {
  std::vector<std::pair<double, double>> out;
  for (const Match& m : associate(first, second, offset, max_difference))
    out.emplace_back(first[m.first], second[m.second]);
  return out;
}
using Pairs = std::vector<std::pair<double, double>>;
}  // namespace

// Greedy by smallest difference, not nearest neighbour per ground-truth stamp: 1.010-1.006 (0.004) is
// taken first, which leaves 1.000 to pair with 1.017 (0.017), crossing over.
TEST(evalAssociation, GreedyBySmallestDifferenceCanCross) {
  EXPECT_EQ(matchedStamps({1.000, 1.010}, {1.006, 1.017}, 0.0, 0.02),
            (Pairs{{1.000, 1.017}, {1.010, 1.006}}));
}

// Exactly representable stamps make three candidates tie at 1/128 s; the tie is broken by the first stamp,
// then the second, so 2.0 takes the earlier 1.9921875 and 2.015625 can still have 2.0078125.
TEST(evalAssociation, TiesBreakByFirstThenSecondStamp) {
  const double d = 1.0 / 128;
  EXPECT_EQ(matchedStamps({2.0, 2.0 + 2 * d}, {2.0 - d, 2.0 + d}, 0.0, 0.02),
            (Pairs{{2.0, 2.0 - d}, {2.0 + 2 * d, 2.0 + d}}));
}

TEST(evalAssociation, MaxDifferenceIsExclusiveAndEachStampUsedOnce) {
  const double d = 1.0 / 64;
  EXPECT_TRUE(matchedStamps({3.0}, {3.0 + d}, 0.0, d).empty());
  EXPECT_EQ(matchedStamps({3.0}, {3.0 + d}, 0.0, 2 * d).size(), 1u);
  // One estimate near two ground-truth stamps matches only the closer one.
  EXPECT_EQ(matchedStamps({5.0, 5.01}, {5.008}, 0.0, 0.02), (Pairs{{5.01, 5.008}}));
}

TEST(evalAssociation, OffsetIsAddedToTheSecondStamps) {
  EXPECT_EQ(matchedStamps({1.000, 1.010}, {0.506, 0.517}, 0.5, 0.02),
            (Pairs{{1.000, 0.517}, {1.010, 0.506}}));
  EXPECT_TRUE(matchedStamps({1.0}, {1.0}, 0.5, 0.02).empty());
}

TEST(evalAssociation, ResultIsOrderedByFirstStamp) {
  const std::vector<double> first = {0.0, 0.1, 0.2, 0.3, 0.4};
  const std::vector<double> second = {0.39, 0.005, 0.21, 0.1};
  std::vector<double> sorted_second = second;
  std::sort(sorted_second.begin(), sorted_second.end());
  const auto matches = associate(first, sorted_second, 0.0, 0.02);
  ASSERT_EQ(matches.size(), 4u);
  for (std::size_t k = 1; k < matches.size(); ++k) EXPECT_LT(matches[k - 1].first, matches[k].first);
}

}  // namespace bmp::eval

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "bmp/common/se3.hpp"
#include "bmp/common/timing.hpp"

namespace bmp {
namespace {

TEST(Timing, PercentilesLikeNumpy) {
  TimingStats s;
  for (double v : {5.0, 1.0, 3.0, 2.0, 4.0}) s.add(v);
  EXPECT_DOUBLE_EQ(s.median(), 3.0);
  EXPECT_DOUBLE_EQ(s.percentile(95), 4.8);  // numpy.percentile([1..5], 95)
  EXPECT_DOUBLE_EQ(s.mean(), 3.0);
  EXPECT_TRUE(std::isnan(TimingStats().median()));
  EXPECT_DOUBLE_EQ(percentileOf({1.0, 2.0, 3.0, 4.0}, 50), 2.5);
  // Selection gives what the sorted list gives, at every rank and between ranks, duplicates included.
  std::vector<double> values;
  for (int i = 0; i < 1001; ++i) values.push_back(static_cast<double>((i * 7919) % 613) * 0.5);
  std::vector<double> sorted = values;
  std::sort(sorted.begin(), sorted.end());
  for (double pct : {0.0, 0.05, 12.3, 50.0, 95.0, 99.99, 100.0}) {
    const double rank = pct / 100.0 * 1000.0;
    const auto lo = static_cast<std::size_t>(std::floor(rank)),
               hi = static_cast<std::size_t>(std::ceil(rank));
    EXPECT_DOUBLE_EQ(percentileOf(values, pct), sorted[lo] + (sorted[hi] - sorted[lo]) * (rank - lo)) << pct;
  }
}

TEST(SE3, ExpLogRoundTripAndAngle) {
  Eigen::Matrix<double, 6, 1> xi;
  xi << 0.3, -0.1, 0.5, 0.2, -0.4, 0.1;
  const SE3 T = expSE3(xi);
  EXPECT_LT((logSE3(T) - xi).norm(), 1e-10);
  EXPECT_NEAR(rotationAngle(T), xi.tail<3>().norm(), 1e-12);
  const SE3 small = expSE3((Eigen::Matrix<double, 6, 1>() << 0, 0, 0, 1e-9, 0, 0).finished());
  EXPECT_NEAR(rotationAngle(small), 1e-9, 1e-15);
}

}  // namespace
}  // namespace bmp

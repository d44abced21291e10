#include <cmath>

#include <gtest/gtest.h>

#include "eval/error_stats.hpp"

namespace bmp::eval {

TEST(evalErrorStats, OddCountByHand) {
  const ErrorStats s = computeStats({3.0, 1.0, 2.0});
  EXPECT_EQ(s.count, 3u);
  EXPECT_DOUBLE_EQ(s.mean, 2.0);
  EXPECT_DOUBLE_EQ(s.median, 2.0);
  EXPECT_DOUBLE_EQ(s.rmse, std::sqrt(14.0 / 3.0));
  EXPECT_DOUBLE_EQ(s.std, std::sqrt(2.0 / 3.0));  // population std, not sample std (which would be 1)
  EXPECT_DOUBLE_EQ(s.min, 1.0);
  EXPECT_DOUBLE_EQ(s.max, 3.0);
}

TEST(evalErrorStats, EvenCountMedianAveragesTheMiddlePair) {
  const ErrorStats s = computeStats({4.0, 1.0, 10.0, 2.0});
  EXPECT_DOUBLE_EQ(s.median, 3.0);
}

TEST(evalErrorStats, EmptyIsNaNAndScaledKeepsCount) {
  const ErrorStats empty = computeStats({});
  EXPECT_EQ(empty.count, 0u);
  EXPECT_TRUE(std::isnan(empty.rmse));
  const ErrorStats deg = scaled(computeStats({M_PI}), 180.0 / M_PI);
  EXPECT_EQ(deg.count, 1u);
  EXPECT_DOUBLE_EQ(deg.max, 180.0);
}

}  // namespace bmp::eval

#include <gtest/gtest.h>

#include <cmath>

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

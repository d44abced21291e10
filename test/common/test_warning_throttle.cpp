// A flood of bad input cannot flood the log: per kind, the first few warnings are written, then one line
// every few seconds, saying how many were left out.
#include <gtest/gtest.h>

#include "bmp/common/warning_throttle.hpp"

namespace bmp {
namespace {

TEST(WarningThrottle, TheFirstFewThenOneLineEveryFewSecondsWithTheCountLeftOut) {
  WarningThrottle throttle(3, 5'000'000);
  for (int i = 0; i < 3; ++i) {
    const auto admitted = throttle.admit("frames", 1'000'000);
    ASSERT_TRUE(admitted);
    EXPECT_EQ(*admitted, 0);
  }
  for (int i = 0; i < 1000; ++i) EXPECT_FALSE(throttle.admit("frames", 2'000'000));
  EXPECT_TRUE(throttle.admit("poses", 2'000'000)) << "each kind has its own few";
  const auto later = throttle.admit("frames", 6'000'001);
  ASSERT_TRUE(later);
  EXPECT_EQ(*later, 1000);
  EXPECT_FALSE(throttle.admit("frames", 6'000'002));
  EXPECT_EQ(leftOutNote(1000), " (1000 more like it not shown)");
  EXPECT_EQ(leftOutNote(0), "");
}

}  // namespace
}  // namespace bmp

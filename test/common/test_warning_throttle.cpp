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

// The ones left out after the last line written are told once, by whoever closes: no later warning would.
TEST(WarningThrottle, TheCountLeftOutAtTheEndIsTakenOnce) {
  WarningThrottle throttle(2, 5'000'000);
  EXPECT_EQ(throttle.takeLeftOut("files"), 0);
  for (int i = 0; i < 6; ++i) throttle.admit("files", 1'000'000);
  EXPECT_EQ(throttle.takeLeftOut("files"), 4);
  EXPECT_EQ(throttle.takeLeftOut("files"), 0);
  const auto next = throttle.admit("files", 7'000'000);
  ASSERT_TRUE(next);
  EXPECT_EQ(*next, 0) << "already told";
}

}  // namespace
}  // namespace bmp

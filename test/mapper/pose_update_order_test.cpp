// Pose updates out of order: a keyframe's pose from an older optimisation never replaces a newer one.
#include <gtest/gtest.h>

#include "mapper/pose_update_order.hpp"
#include "mapper_test_util.hpp"

namespace bmp::mapper {
namespace {

TEST(PoseUpdateOrder, AnOlderUpdateOfAKeyframeIsStaleANewerOrEqualOneIsTaken) {
  PoseUpdateOrder order;
  std::vector<std::string> stale;
  auto taken = order.notOlder({{1, test::translation(1, 0, 0)}, {2, SE3::Identity()}}, 5000, stale);
  ASSERT_EQ(taken.size(), 2u);
  for (const auto& u : taken) order.taken(u.id, 5000);

  taken = order.notOlder({{1, test::translation(9, 0, 0)}, {3, SE3::Identity()}}, 4000, stale);
  ASSERT_EQ(taken.size(), 1u);
  EXPECT_EQ(taken[0].id, 3) << "a keyframe with no pose taken yet";
  ASSERT_EQ(stale.size(), 1u);
  EXPECT_EQ(stale[0], "keyframe 1: stamped 4000 us, older than its pose of 5000 us");

  stale.clear();
  EXPECT_EQ(order.notOlder({{1, SE3::Identity()}}, 5000, stale).size(), 1u) << "the same optimisation's";
  EXPECT_EQ(order.notOlder({{2, SE3::Identity()}}, 6000, stale).size(), 1u);
  EXPECT_TRUE(stale.empty());

  order.clear();  // a new map
  EXPECT_EQ(order.notOlder({{1, SE3::Identity()}}, 1, stale).size(), 1u);
}

}  // namespace
}  // namespace bmp::mapper

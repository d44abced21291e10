// Pose updates out of order: a keyframe's pose from an older optimisation never replaces a newer one.
#include <gtest/gtest.h>

#include <limits>
#include <string>
#include <vector>

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

// One update stamped far in the future (a forged stamp, INT64_MAX) once made every real update after it look
// older, for the rest of the run: a message stamped over a minute beyond the newest keyframe is refused
// whole.
TEST(PoseUpdateOrder, AStampFarBeyondTheNewestKeyframeIsRefusedWhole) {
  PoseUpdateOrder order;
  std::vector<std::string> stale;
  order.keyframeMapped(10'000'000);
  const int64_t forged = std::numeric_limits<int64_t>::max();
  EXPECT_TRUE(order.notOlder({{1, SE3::Identity()}, {2, SE3::Identity()}}, forged, stale).empty());
  ASSERT_EQ(stale.size(), 2u);
  EXPECT_NE(stale[0].find("keyframe 1: stamped " + std::to_string(forged) + " us"), std::string::npos)
      << stale[0];
  EXPECT_NE(stale[0].find("after the newest keyframe: not this map's"), std::string::npos) << stale[0];
  stale.clear();
  // A BA update a few seconds after its keyframe, as the tracker sends them, is taken.
  EXPECT_EQ(order.notOlder({{1, SE3::Identity()}}, 10'000'000 + 5'000'000, stale).size(), 1u);
  EXPECT_EQ(
      order.notOlder({{1, SE3::Identity()}}, 10'000'000 + PoseUpdateOrder::kMaxAheadOfKeyframesUs, stale)
          .size(),
      1u);
  EXPECT_TRUE(stale.empty());
}

// The capture restarted (stamps from the start again) while the tracker kept its map: its updates, stamped
// in the new time base, were all refused as older than the poses taken before the restart. A keyframe stamped
// before the newest one starts the stamps again.
TEST(PoseUpdateOrder, AKeyframeStampedBeforeTheNewestStartsTheStampsAgain) {
  PoseUpdateOrder order;
  std::vector<std::string> stale;
  order.keyframeMapped(500'000'000);
  order.taken(1, 501'000'000);
  EXPECT_TRUE(order.notOlder({{1, SE3::Identity()}}, 2'000'000, stale).empty())
      << "before the restart is seen";
  stale.clear();
  order.keyframeMapped(1'000'000);  // the restarted stream's first keyframe
  EXPECT_EQ(order.notOlder({{1, SE3::Identity()}}, 2'000'000, stale).size(), 1u);
  EXPECT_TRUE(stale.empty());
}

}  // namespace
}  // namespace bmp::mapper

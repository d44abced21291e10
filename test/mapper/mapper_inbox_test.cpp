// bmp-mapper's inbox between its receive thread and its loop: arrival order kept across keyframes and pose
// updates, a budget in bytes (a flood of huge forged keyframes cannot fill memory), refusals counted.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "mapper/lcm/mapper_inbox.hpp"

namespace bmp::mapper {
namespace {

keyframe_t keyframeOf(int64_t id, std::size_t bytes) {
  keyframe_t m{};
  m.id = id;
  m.color.size = static_cast<int32_t>(bytes);
  m.color.data.assign(bytes, 7);
  return m;
}

keyframe_poses_t posesOf(int64_t utime) {
  keyframe_poses_t m{};
  m.utime = utime;
  m.num_keyframes = 1;
  m.ids = {1};
  m.T_world_cam.resize(1);
  return m;
}

TEST(MapperInbox, KeepsArrivalOrderAcrossKeyframesAndPoseUpdates) {
  MapperInbox inbox(1 << 20);
  ASSERT_TRUE(inbox.offer(keyframeOf(1, 1000)));
  ASSERT_TRUE(inbox.offer(posesOf(5)));
  ASSERT_TRUE(inbox.offer(keyframeOf(2, 1000)));
  const auto first = inbox.tryPop();
  ASSERT_TRUE(first && std::holds_alternative<keyframe_t>(*first));
  EXPECT_EQ(std::get<keyframe_t>(*first).id, 1);
  const auto second = inbox.tryPop();
  ASSERT_TRUE(second && std::holds_alternative<keyframe_poses_t>(*second));
  EXPECT_EQ(std::get<keyframe_poses_t>(*second).utime, 5);
  const auto third = inbox.tryPop();
  ASSERT_TRUE(third && std::holds_alternative<keyframe_t>(*third));
  EXPECT_EQ(std::get<keyframe_t>(*third).id, 2);
  EXPECT_FALSE(inbox.tryPop());
  EXPECT_EQ(inbox.waitingBytes(), 0u);
  EXPECT_EQ(inbox.refusedCount(), 0);
}

TEST(MapperInbox, ABudgetInBytesRefusesAndCountsWhatDoesNotFit) {
  const std::size_t kf = 300000;
  MapperInbox inbox(1 << 20);  // three such keyframes and a bit
  for (int64_t id = 0; id < 3; ++id) EXPECT_TRUE(inbox.offer(keyframeOf(id, kf))) << id;
  EXPECT_FALSE(inbox.offer(keyframeOf(3, kf)));
  EXPECT_TRUE(inbox.offer(posesOf(1)));  // a small message still fits
  EXPECT_EQ(inbox.refusedCount(), 1);
  EXPECT_GT(inbox.waitingBytes(), 3 * kf);
  // Taken by the loop, the bytes are free again.
  ASSERT_TRUE(inbox.tryPop());
  EXPECT_TRUE(inbox.offer(keyframeOf(4, kf)));
  EXPECT_FALSE(inbox.offer(keyframeOf(5, kf)));
  EXPECT_EQ(inbox.refusedCount(), 2);
}

// A keyframe larger than the whole budget is still taken when nothing waits: LCM's own checks bound a
// message, and a small budget must not shut the mapper out of a big camera's keyframes.
TEST(MapperInbox, OneMessageAlwaysFitsAnEmptyInbox) {
  MapperInbox inbox(1000);
  EXPECT_TRUE(inbox.offer(keyframeOf(0, 5000)));
  EXPECT_FALSE(inbox.offer(keyframeOf(1, 10)));
  ASSERT_TRUE(inbox.tryPop());
  EXPECT_TRUE(inbox.offer(keyframeOf(2, 5000)));
}

TEST(MapperInbox, AfterCloseOffersAreRefusedAndWhatWaitsIsStillTaken) {
  MapperInbox inbox(1 << 20);
  ASSERT_TRUE(inbox.offer(keyframeOf(0, 100)));
  inbox.close();
  EXPECT_FALSE(inbox.offer(keyframeOf(1, 100)));
  EXPECT_EQ(inbox.refusedCount(), 1);
  EXPECT_TRUE(inbox.tryPop());
  EXPECT_FALSE(inbox.popFor(std::chrono::milliseconds(1)));
  EXPECT_EQ(inbox.waitingBytes(), 0u);
}

// The receive thread offers while the loop takes: every message arrives once, in order.
TEST(MapperInbox, AReceiveThreadAndALoopHandEveryMessageOverInOrder) {
  MapperInbox inbox(64 << 10);
  constexpr int64_t kMessages = 2000;
  std::thread receiver([&] {
    for (int64_t id = 0; id < kMessages; ++id)
      while (!inbox.offer(keyframeOf(id, 4000))) std::this_thread::yield();  // the test waits; the node drops
  });
  int64_t expected = 0;
  while (expected < kMessages) {
    const auto m = inbox.popFor(std::chrono::milliseconds(100));
    if (!m) continue;
    ASSERT_EQ(std::get<keyframe_t>(*m).id, expected);
    ++expected;
  }
  receiver.join();
  EXPECT_EQ(inbox.waitingBytes(), 0u);
}

}  // namespace
}  // namespace bmp::mapper

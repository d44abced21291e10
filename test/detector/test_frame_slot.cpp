#include <gtest/gtest.h>

#include <chrono>
#include <future>
#include <thread>

#include "detector/frame_slot.hpp"

namespace bmp::detector {
namespace {

using namespace std::chrono_literals;

TEST(DetectorFrameSlot, LatestModeKeepsTheNewestAndCountsDrops) {
  FrameSlot<int> slot(QueueMode::kLatest, 64);
  EXPECT_EQ(slot.push(1), 0u);
  EXPECT_EQ(slot.push(2), 1u);
  EXPECT_EQ(slot.push(3), 1u);
  EXPECT_EQ(slot.size(), 1u);
  EXPECT_EQ(slot.pop(), 3);
  EXPECT_EQ(slot.push(4), 0u);
  EXPECT_EQ(slot.pop(), 4);
}

TEST(DetectorFrameSlot, EveryModeKeepsAllInOrder) {
  FrameSlot<int> slot(QueueMode::kEvery, 8);
  for (int i = 0; i < 5; ++i) EXPECT_EQ(slot.push(i), 0u);
  for (int i = 0; i < 5; ++i) EXPECT_EQ(slot.pop(), i);
}

TEST(DetectorFrameSlot, EveryModeProducerWaitsWhenFull) {
  FrameSlot<int> slot(QueueMode::kEvery, 2);
  slot.push(1);
  slot.push(2);
  auto third = std::async(std::launch::async, [&] { return slot.push(3); });
  EXPECT_EQ(third.wait_for(100ms), std::future_status::timeout);
  EXPECT_EQ(slot.pop(), 1);
  EXPECT_EQ(third.get(), 0u);
  EXPECT_EQ(slot.pop(), 2);
  EXPECT_EQ(slot.pop(), 3);
}

TEST(DetectorFrameSlot, CloseWakesTheConsumerAfterDraining) {
  FrameSlot<int> slot(QueueMode::kEvery, 4);
  slot.push(7);
  auto consumer = std::async(std::launch::async, [&] {
    std::vector<int> got;
    while (auto item = slot.pop()) got.push_back(*item);
    return got;
  });
  std::this_thread::sleep_for(50ms);
  slot.close();
  EXPECT_EQ(consumer.get(), std::vector<int>{7});
  EXPECT_EQ(slot.push(8), 1u);  // refused after close
}

TEST(DetectorFrameSlot, ParsesModes) {
  EXPECT_EQ(parseQueueMode("latest"), QueueMode::kLatest);
  EXPECT_EQ(parseQueueMode("every"), QueueMode::kEvery);
  EXPECT_THROW(parseQueueMode("newest"), std::invalid_argument);
}

}  // namespace
}  // namespace bmp::detector

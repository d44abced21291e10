#include "bmp/common/bounded_queue.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <future>
#include <memory>
#include <thread>
#include <vector>

namespace bmp {
namespace {

using namespace std::chrono_literals;

// The detector's 'latest' mode: one slot, the newest frame replaces the waiting one, each replacement
// counted.
TEST(BoundedQueue, CapacityOneDropOldestKeepsTheNewestAndCountsDrops) {
  BoundedQueue<int> queue(1, WhenFull::kDropOldest);
  EXPECT_EQ(queue.push(1), 0u);
  EXPECT_EQ(queue.push(2), 1u);
  EXPECT_EQ(queue.push(3), 1u);
  EXPECT_EQ(queue.size(), 1u);
  EXPECT_EQ(queue.pop(), 3);
  EXPECT_EQ(queue.push(4), 0u);
  EXPECT_EQ(queue.pop(), 4);
  EXPECT_EQ(queue.dropped(), 2u);
}

// Oldest gives way at any capacity: what waits is always the newest `capacity` items, in order.
TEST(BoundedQueue, DropOldestKeepsTheNewestItemsInOrder) {
  BoundedQueue<int> queue(3, WhenFull::kDropOldest);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(queue.push(i), 0u);
  EXPECT_EQ(queue.push(3), 1u);
  EXPECT_EQ(queue.push(4), 1u);
  EXPECT_EQ(queue.dropped(), 2u);
  for (int i = 2; i < 5; ++i) EXPECT_EQ(queue.tryPop(), i);
  EXPECT_EQ(queue.tryPop(), std::nullopt);
}

// The detector's 'every' mode.
TEST(BoundedQueue, WaitKeepsAllInOrder) {
  BoundedQueue<int> queue(8, WhenFull::kWait);
  for (int i = 0; i < 5; ++i) EXPECT_EQ(queue.push(i), 0u);
  for (int i = 0; i < 5; ++i) EXPECT_EQ(queue.pop(), i);
  EXPECT_EQ(queue.dropped(), 0u);
}

TEST(BoundedQueue, WaitMakesTheProducerWaitWhenFull) {
  BoundedQueue<int> queue(2, WhenFull::kWait);
  queue.push(1);
  queue.push(2);
  auto third = std::async(std::launch::async, [&] { return queue.push(3); });
  EXPECT_EQ(third.wait_for(100ms), std::future_status::timeout);
  EXPECT_EQ(queue.pop(), 1);
  EXPECT_EQ(third.get(), 0u);
  EXPECT_EQ(queue.pop(), 2);
  EXPECT_EQ(queue.pop(), 3);
}

TEST(BoundedQueue, CloseReleasesAWaitingProducerAndDiscardsItsItem) {
  BoundedQueue<int> queue(1, WhenFull::kWait);
  queue.push(1);
  auto second = std::async(std::launch::async, [&] { return queue.push(2); });
  EXPECT_EQ(second.wait_for(50ms), std::future_status::timeout);
  queue.close();
  EXPECT_EQ(second.get(), 1u);
  EXPECT_EQ(queue.pop(), 1);
  EXPECT_EQ(queue.pop(), std::nullopt);
}

TEST(BoundedQueue, CloseWakesTheConsumerAfterDraining) {
  BoundedQueue<int> queue(4, WhenFull::kWait);
  queue.push(7);
  auto consumer = std::async(std::launch::async, [&] {
    std::vector<int> got;
    while (auto item = queue.pop()) got.push_back(*item);
    return got;
  });
  std::this_thread::sleep_for(50ms);
  queue.close();
  EXPECT_EQ(consumer.get(), std::vector<int>{7});
  EXPECT_EQ(queue.push(8), 1u);  // refused after close, counted as dropped
  EXPECT_EQ(queue.dropped(), 1u);
}

// The tracker's keyframe hand-over: a full queue refuses the new item and keeps what waits.
TEST(BoundedQueue, TryPushRefusesWhenFullOrClosedWithoutDisplacing) {
  BoundedQueue<std::unique_ptr<int>> queue(2);
  EXPECT_TRUE(queue.tryPush(std::make_unique<int>(1)));
  EXPECT_FALSE(queue.full());
  EXPECT_TRUE(queue.tryPush(std::make_unique<int>(2)));
  EXPECT_TRUE(queue.full());
  EXPECT_FALSE(queue.tryPush(std::make_unique<int>(3)));
  EXPECT_EQ(queue.size(), 2u);
  EXPECT_EQ(queue.dropped(), 0u);
  EXPECT_EQ(**queue.tryPop(), 1);
  queue.close();
  EXPECT_FALSE(queue.tryPush(std::make_unique<int>(4)));
  EXPECT_EQ(**queue.pop(), 2);
  EXPECT_EQ(queue.pop(), std::nullopt);
}

TEST(BoundedQueue, PopForReturnsAnItemOrNothingAfterTheTimeout) {
  BoundedQueue<int> q(2, WhenFull::kDropOldest);
  EXPECT_FALSE(q.popFor(std::chrono::milliseconds(5)).has_value());
  q.push(4);
  EXPECT_EQ(q.popFor(std::chrono::milliseconds(5)).value_or(-1), 4);
  std::thread producer([&q] { q.push(9); });
  EXPECT_EQ(q.popFor(std::chrono::seconds(30)).value_or(-1), 9);  // woken by the push, not the timeout
  producer.join();
}

TEST(BoundedQueue, ZeroCapacityHoldsOne) {
  BoundedQueue<int> queue(0, WhenFull::kDropOldest);
  EXPECT_EQ(queue.capacity(), 1u);
  EXPECT_EQ(queue.push(1), 0u);
  EXPECT_EQ(queue.push(2), 1u);
  EXPECT_EQ(queue.pop(), 2);
}

}  // namespace
}  // namespace bmp

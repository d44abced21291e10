#pragma once
// A fixed-capacity queue between two stages, so a slow consumer makes the producer wait or lose items
// visibly instead of growing memory. What push() does when full is chosen once, per queue:
//   kWait        the producer waits for space; nothing is lost (lockstep runs).
//   kDropOldest  the oldest waiting item gives way (counted), so the consumer works on fresh data; with
//                capacity 1 the newest item replaces the waiting one.
// tryPush() never waits and never displaces anything: a full queue refuses the new item instead.
// The consumer blocks in pop() until an item arrives or the queue is closed, or polls with tryPop().
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <mutex>
#include <optional>

namespace bmp {

enum class WhenFull { kWait, kDropOldest };

template <typename T>
class BoundedQueue {
 public:
  // capacity: items held at once, at least 1 (0 is taken as 1, so a queue can always hand something on).
  explicit BoundedQueue(std::size_t capacity, WhenFull when_full = WhenFull::kWait)
      : capacity_(capacity > 0 ? capacity : 1), when_full_(when_full) {}

  // Returns how many items this push lost: the oldest one that gave way (kDropOldest), or this one when the
  // queue is closed (it is discarded). Waits for space under kWait, until close().
  std::size_t push(T item) {
    std::size_t lost = 0;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      if (when_full_ == WhenFull::kWait)
        space_.wait(lock, [this] { return closed_ || items_.size() < capacity_; });
      if (closed_) {
        ++dropped_;
        return 1;
      }
      while (items_.size() >= capacity_) {
        items_.pop_front();
        ++lost;
      }
      items_.push_back(std::move(item));
      dropped_ += lost;
    }
    ready_.notify_one();
    return lost;
  }

  // Never waits, never displaces: false (the item is discarded, not counted) when full or closed.
  bool tryPush(T item) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (closed_ || items_.size() >= capacity_) return false;
      items_.push_back(std::move(item));
    }
    ready_.notify_one();
    return true;
  }

  // Blocks until an item arrives; nullopt once closed and drained (what was queued is still handed out).
  std::optional<T> pop() {
    std::unique_lock<std::mutex> lock(mutex_);
    ready_.wait(lock, [this] { return closed_ || !items_.empty(); });
    return takeFront(lock);
  }

  // Waits at most timeout for an item; nullopt when none came (or closed and drained).
  template <typename Rep, typename Period>
  std::optional<T> popFor(std::chrono::duration<Rep, Period> timeout) {
    std::unique_lock<std::mutex> lock(mutex_);
    ready_.wait_for(lock, timeout, [this] { return closed_ || !items_.empty(); });
    return takeFront(lock);
  }

  // nullopt when empty.
  std::optional<T> tryPop() {
    std::unique_lock<std::mutex> lock(mutex_);
    return takeFront(lock);
  }

  // Wakes every waiter; later pushes are refused.
  void close() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      closed_ = true;
    }
    ready_.notify_all();
    space_.notify_all();
  }

  std::size_t size() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return items_.size();
  }
  bool full() const { return size() >= capacity_; }
  std::size_t capacity() const { return capacity_; }
  WhenFull whenFull() const { return when_full_; }
  // Items push() lost since construction (displaced, or discarded after close()).
  std::size_t dropped() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return dropped_;
  }

 private:
  std::optional<T> takeFront(std::unique_lock<std::mutex>& lock) {
    if (items_.empty()) return std::nullopt;
    std::optional<T> item(std::move(items_.front()));
    items_.pop_front();
    lock.unlock();
    space_.notify_one();
    return item;
  }

  const std::size_t capacity_;
  const WhenFull when_full_;
  mutable std::mutex mutex_;
  std::condition_variable ready_;
  std::condition_variable space_;
  std::deque<T> items_;
  std::size_t dropped_ = 0;
  bool closed_ = false;
};

}  // namespace bmp

#include "tracker/detection_book.hpp"

namespace bmp::tracker {

void DetectionBook::add(int64_t seq, FrameBoxes boxes) {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    by_seq_[seq] = std::move(boxes);
    while (by_seq_.size() > capacity_) {
      by_seq_.erase(by_seq_.begin());
      ++discarded_;
    }
  }
  arrived_.notify_all();
}

std::optional<FrameBoxes> DetectionBook::take(int64_t seq, int64_t utime, std::chrono::milliseconds wait) {
  std::unique_lock<std::mutex> lock(mutex_);
  arrived_.wait_for(lock, wait, [&] { return by_seq_.count(seq) > 0; });
  const auto it = by_seq_.find(seq);
  if (it == by_seq_.end() || it->second.utime != utime) return std::nullopt;
  FrameBoxes out = std::move(it->second);
  by_seq_.erase(it);
  return out;
}

std::size_t DetectionBook::size() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return by_seq_.size();
}

int64_t DetectionBook::discarded() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return discarded_;
}

}  // namespace bmp::tracker

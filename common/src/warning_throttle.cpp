#include "bmp/common/warning_throttle.hpp"

#include <chrono>

namespace bmp {

std::optional<int64_t> WarningThrottle::admit(const std::string& kind, int64_t now_us) {
  const std::lock_guard<std::mutex> lock(mutex_);
  State& s = states_[kind];
  ++s.count;
  if (s.count > each_named_ && now_us - s.last_written_us < summary_every_us_) {
    ++s.left_out;
    return std::nullopt;
  }
  const int64_t left_out = s.left_out;
  s.left_out = 0;
  s.last_written_us = now_us;
  return left_out;
}

std::optional<int64_t> WarningThrottle::admit(const std::string& kind) {
  return admit(kind, std::chrono::duration_cast<std::chrono::microseconds>(
                         std::chrono::steady_clock::now().time_since_epoch())
                         .count());
}

int64_t WarningThrottle::takeLeftOut(const std::string& kind) {
  const std::lock_guard<std::mutex> lock(mutex_);
  const auto it = states_.find(kind);
  if (it == states_.end()) return 0;
  const int64_t left_out = it->second.left_out;
  it->second.left_out = 0;
  return left_out;
}

std::string leftOutNote(int64_t left_out) {
  return left_out > 0 ? " (" + std::to_string(left_out) + " more like it not shown)" : "";
}

}  // namespace bmp

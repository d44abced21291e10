#include "capture/pacer.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <thread>

namespace bmp::capture {

RateMode parseRateMode(const std::string& text) {
  if (text == "realtime") return RateMode::kRealtime;
  if (text == "fast") return RateMode::kFast;
  if (text == "lockstep") return RateMode::kLockstep;
  throw std::invalid_argument("rate mode must be realtime, fast or lockstep, got '" + text + "'");
}

const char* toString(RateMode mode) {
  switch (mode) {
    case RateMode::kRealtime:
      return "realtime";
    case RateMode::kFast:
      return "fast";
    case RateMode::kLockstep:
      return "lockstep";
  }
  return "unknown";
}

Pacer::Pacer(RateMode mode, double speed) : mode_(mode), speed_(speed) {
  if (!(speed >= kMinSpeed && speed <= kMaxSpeed))
    throw std::invalid_argument("speed must be " + std::to_string(kMinSpeed) + " to " +
                                std::to_string(kMaxSpeed));
}

double Pacer::waitFor(double stamp) const {
  if (mode_ != RateMode::kRealtime || !first_stamp_) return 0.0;
  const double since_origin =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - origin_).count();
  return std::max(0.0, (stamp - *first_stamp_) / speed_ - since_origin);
}

bool Pacer::waitUntilDue(double stamp, const std::function<bool()>& between) {
  if (mode_ != RateMode::kRealtime) return true;
  const auto now = std::chrono::steady_clock::now();
  if (!first_stamp_) {
    first_stamp_ = stamp;
    origin_ = now;
    return true;
  }
  // Bounded before the conversion to the clock's integer ticks (a century: stamps are checked to be under
  // 1e11 s, and speed at least kMinSpeed, so only a gap in them gets near it).
  const double offset_s = std::min((stamp - *first_stamp_) / speed_, 3.2e9);
  const auto due = origin_ + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                 std::chrono::duration<double>(offset_s));
  if (due <= now) {
    lateness_ms_ = std::chrono::duration<double, std::milli>(now - due).count();
    return true;
  }
  lateness_ms_ = 0.0;
  for (auto t = now; t < due; t = std::chrono::steady_clock::now()) {
    std::this_thread::sleep_until(std::min(due, t + std::chrono::milliseconds(kSliceMs)));
    if (between && between()) return false;
  }
  return true;
}

}  // namespace bmp::capture

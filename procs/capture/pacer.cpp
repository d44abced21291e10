#include "capture/pacer.hpp"

#include <stdexcept>
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
  if (!(speed > 0.0)) throw std::invalid_argument("speed must be positive");
}

void Pacer::waitUntilDue(double stamp) {
  if (mode_ != RateMode::kRealtime) return;
  const auto now = std::chrono::steady_clock::now();
  if (!first_stamp_) {
    first_stamp_ = stamp;
    origin_ = now;
    return;
  }
  const auto due = origin_ + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                 std::chrono::duration<double>((stamp - *first_stamp_) / speed_));
  if (due > now) {
    std::this_thread::sleep_until(due);
    lateness_ms_ = 0.0;
  } else {
    lateness_ms_ = std::chrono::duration<double, std::milli>(now - due).count();
  }
}

}  // namespace bmp::capture

#pragma once
// When to publish the next frame: at the recorded rate times a speed factor, or as fast as possible.
// Lockstep (wait for the consumer's answer) is done by the caller, which owns the LCM connection.
#include <chrono>
#include <optional>
#include <string>

namespace bmp::capture {

enum class RateMode { kRealtime, kFast, kLockstep };

RateMode parseRateMode(const std::string& text);  // "realtime" | "fast" | "lockstep"; throws invalid_argument
const char* toString(RateMode mode);

class Pacer {
 public:
  Pacer(RateMode mode, double speed);
  // Sleeps until a frame recorded at `stamp` (seconds) is due. The first call sets the time origin.
  void waitUntilDue(double stamp);
  // How late the last frame was against its schedule, ms (0 in fast and lockstep modes).
  double lastLatenessMs() const { return lateness_ms_; }

 private:
  RateMode mode_;
  double speed_;
  std::optional<double> first_stamp_;
  std::chrono::steady_clock::time_point origin_;
  double lateness_ms_ = 0.0;
};

}  // namespace bmp::capture

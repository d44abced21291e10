#pragma once
// When to publish the next frame: at the recorded rate times a speed factor, or as fast as possible.
// Lockstep (wait for the consumer's answer) is done by the caller, which owns the LCM connection.
#include <chrono>
#include <functional>
#include <optional>
#include <string>

namespace bmp::capture {

enum class RateMode { kRealtime, kFast, kLockstep };

RateMode parseRateMode(const std::string& text);  // "realtime" | "fast" | "lockstep"; throws invalid_argument
const char* toString(RateMode mode);

class Pacer {
 public:
  // speed: kMinSpeed to kMaxSpeed (std::invalid_argument otherwise).
  Pacer(RateMode mode, double speed);
  // Sleeps until a frame recorded at `stamp` (seconds) is due; the first call sets the time origin. A long
  // wait (a slow speed, a gap in the stamps) is slept in slices of kSliceMs, calling `between` after each:
  // it keeps heartbeats going and returns true to stop waiting (a stop was asked for). Returns false when
  // stopped so.
  bool waitUntilDue(double stamp, const std::function<bool()>& between = {});
  // How long the frame at `stamp` will wait from now, seconds (0 when due, and in fast and lockstep modes).
  double waitFor(double stamp) const;
  static constexpr double kMinSpeed = 1e-3;
  static constexpr double kMaxSpeed = 1e3;
  static constexpr int kSliceMs = 100;
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

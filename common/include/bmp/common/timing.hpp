#pragma once
// Timing statistics for loops: every stage records its run time and reports median and 95th percentile.
#include <chrono>
#include <cstddef>
#include <string>
#include <vector>

namespace bmp {

class TimingStats {
 public:
  void add(double milliseconds) { samples_.push_back(milliseconds); }
  std::size_t count() const { return samples_.size(); }
  bool empty() const { return samples_.empty(); }
  double median() const { return percentile(50.0); }
  double p95() const { return percentile(95.0); }
  double mean() const;
  double max() const;
  // Linear interpolation between closest ranks (numpy's default); NaN when empty.
  double percentile(double pct) const;
  // "median 12.3 ms, p95 15.0 ms, n 100"
  std::string summary() const;
  const std::vector<double>& samples() const { return samples_; }

 private:
  std::vector<double> samples_;
};

class Stopwatch {
 public:
  Stopwatch() : start_(std::chrono::steady_clock::now()) {}
  void restart() { start_ = std::chrono::steady_clock::now(); }
  double elapsedMs() const {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  std::chrono::steady_clock::time_point start_;
};

// Adds the time between construction and destruction to a TimingStats.
class ScopedTimer {
 public:
  explicit ScopedTimer(TimingStats& stats) : stats_(stats) {}
  ~ScopedTimer() { stats_.add(watch_.elapsedMs()); }
  ScopedTimer(const ScopedTimer&) = delete;
  ScopedTimer& operator=(const ScopedTimer&) = delete;

 private:
  TimingStats& stats_;
  Stopwatch watch_;
};

// Adds the time between construction and destruction to a running total in milliseconds: for a stage whose
// work is spread over several calls within one frame.
class ScopedAccumulator {
 public:
  explicit ScopedAccumulator(double& total_ms) : total_ms_(total_ms) {}
  ~ScopedAccumulator() { total_ms_ += watch_.elapsedMs(); }
  ScopedAccumulator(const ScopedAccumulator&) = delete;
  ScopedAccumulator& operator=(const ScopedAccumulator&) = delete;

 private:
  double& total_ms_;
  Stopwatch watch_;
};

// Median and p95 of a vector of samples without building a TimingStats.
double percentileOf(std::vector<double> values, double pct);

}  // namespace bmp

#pragma once
// A flood of bad input must not flood the log. Per kind (a channel, "frames"), the first few warnings are
// each written; after that one line every few seconds stands for those left out since the last. Thread-safe.
#include <cstdint>
#include <map>
#include <mutex>
#include <optional>
#include <string>

namespace bmp {

class WarningThrottle {
 public:
  explicit WarningThrottle(int each_named = 5, int64_t summary_every_us = 5'000'000)
      : each_named_(each_named), summary_every_us_(summary_every_us) {}

  // Whether this warning of `kind` is to be written at now_us (a monotonic clock): nullopt to leave it out,
  // else how many of the kind were left out before it (to be said with it).
  std::optional<int64_t> admit(const std::string& kind, int64_t now_us);
  // The same at the steady clock's now.
  std::optional<int64_t> admit(const std::string& kind);
  // How many of `kind` were left out since the last one written, now counted as told: for a closing line,
  // when no later warning of the kind would say it.
  int64_t takeLeftOut(const std::string& kind);

 private:
  struct State {
    int64_t count = 0;
    int64_t last_written_us = 0;
    int64_t left_out = 0;
  };
  const int each_named_;
  const int64_t summary_every_us_;
  std::mutex mutex_;
  std::map<std::string, State> states_;  // one per kind: the callers' fixed names
};

// " (N more like it not shown)" for a left-out count over 0, else "".
std::string leftOutNote(int64_t left_out);

}  // namespace bmp

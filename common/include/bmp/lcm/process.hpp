#pragma once
// The start-up every bmp process shares: standard options (--help, --config, --lcm-url, --print-config),
// configuration loading with validation, the LCM connection, SIGINT/SIGTERM handling and a status
// heartbeat. A main fills a ProcessSpec and hands it to runProcess().
#include <atomic>
#include <cstdint>
#include <exception>
#include <functional>
#include <memory>
#include <string>

#include "bmp/common/arg_parser.hpp"
#include "bmp/common/config.hpp"
#include "bmp/common/config_dir.hpp"  // configDir(), which every process uses
#include "bmp/lcm/channels.hpp"
#include "bmp/lcm/lcm_node.hpp"

namespace bmp {

// Set by SIGINT/SIGTERM. Signals are process-wide, so this is the one process-wide flag we keep.
class StopSignal {
 public:
  StopSignal();   // installs the handlers
  ~StopSignal();  // restores the previous ones
  StopSignal(const StopSignal&) = delete;
  StopSignal& operator=(const StopSignal&) = delete;
  bool requested() const;
  int signalNumber() const;
  void request();  // lets code stop the loop as a signal would (e.g. input finished)
};

// Counters and a once-a-second PROCESS_STATUS heartbeat.
class StatusReporter {
 public:
  StatusReporter(LcmNode& lcm, std::string name, std::string channel = channels::kProcessStatus);
  void received(int64_t n = 1) { received_ += n; }
  void processed(int64_t n = 1) { processed_ += n; }
  void dropped(int64_t n = 1) { dropped_ += n; }
  void lost(int64_t n = 1) { lost_ += n; }  // inputs that never arrived (sequence gaps)
  void malformed(int64_t n = 1) { malformed_ += n; }
  void published(int64_t n = 1) { published_ += n; }
  void setMessage(const std::string& message) { message_ = message; }
  // Publishes on the first call (so a launcher waiting for this process sees it as soon as it listens),
  // then whenever a second has passed since the last heartbeat, or always when force.
  void tick(bool force = false);
  void finish();  // a last heartbeat with state FINISHED
  int64_t receivedCount() const { return received_; }
  int64_t processedCount() const { return processed_; }
  int64_t droppedCount() const { return dropped_; }
  int64_t lostCount() const { return lost_; }
  int64_t malformedCount() const { return malformed_; }
  // Random, non-zero, chosen at construction: what --wait-for counts, as names and pids can repeat.
  int64_t instance() const { return instance_; }

 private:
  void publish(int8_t state);
  LcmNode& lcm_;
  std::string name_;
  std::string channel_;
  std::string message_;
  int64_t instance_;
  int64_t received_ = 0, processed_ = 0, dropped_ = 0, lost_ = 0, malformed_ = 0, published_ = 0;
  int64_t last_received_ = 0, last_published_ = 0;
  int64_t last_utime_ = 0;
  bool announced_ = false;
};

struct ProcessContext {
  const ArgParser& args;
  const Config& config;  // the whole file; the process must read it all before finish()
  LcmNode& lcm;
  StopSignal& stop;
  StatusReporter& status;
};

struct ProcessSpec {
  std::string name;                             // e.g. "bmp-capture"
  std::string summary;                          // one paragraph for --help
  std::string default_config;                   // path relative to the repository's config/ (may be empty)
  std::function<void(ArgParser&)> add_options;  // process-specific options
  // Runs the process; returns the exit code. Exceptions are reported and give exit code 1.
  std::function<int(ProcessContext&)> run;
};

// Thrown by finishConfig under --print-config once the values are printed: runProcess then exits 0 before
// the process starts work.
class ConfigPrinted : public std::exception {
 public:
  const char* what() const noexcept override { return "configuration printed (--print-config)"; }
};

// Rejects unknown keys (ConfigError) and logs every effective value (command-line overrides applied): call
// once the process has read its whole configuration and applied its options, before it starts work. Under
// --print-config it prints them to stdout and throws ConfigPrinted.
void finishConfig(const ProcessContext& context);

// Exit codes: 0 success, 1 runtime failure, 2 bad arguments or configuration.
int runProcess(int argc, char** argv, const ProcessSpec& spec);

// Microseconds since the epoch, wall clock.
int64_t nowUtime();

}  // namespace bmp

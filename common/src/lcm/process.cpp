#include "bmp/lcm/process.hpp"

#include <malloc.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <iostream>
#include <random>
#include <vector>

#include <bmp/process_status_t.hpp>

#include "bmp/common/log.hpp"

namespace bmp {

namespace {
std::atomic<int> g_stop_signal{0};  // written by the signal handler only
struct sigaction g_previous_int {};
struct sigaction g_previous_term {};

extern "C" void onStopSignal(int signo) {
  g_stop_signal.store(signo);
}
}  // namespace

StopSignal::StopSignal() {
  g_stop_signal.store(0);
  struct sigaction action {};
  action.sa_handler = onStopSignal;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, &g_previous_int);
  sigaction(SIGTERM, &action, &g_previous_term);
}

StopSignal::~StopSignal() {
  sigaction(SIGINT, &g_previous_int, nullptr);
  sigaction(SIGTERM, &g_previous_term, nullptr);
}

bool StopSignal::requested() const {
  return g_stop_signal.load() != 0;
}
int StopSignal::signalNumber() const {
  return g_stop_signal.load();
}
void StopSignal::request() {
  g_stop_signal.store(-1);
}

namespace {
int64_t randomInstance() {
  std::random_device device;
  std::uniform_int_distribution<uint64_t> any;
  uint64_t value = 0;
  while (value == 0) value = any(device);  // 0 is what a sender that never set the field carries
  return static_cast<int64_t>(value);
}
}  // namespace

int64_t nowUtime() {
  return std::chrono::duration_cast<std::chrono::microseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

StatusReporter::StatusReporter(LcmNode& lcm, std::string name, std::string channel)
    : lcm_(lcm),
      name_(std::move(name)),
      channel_(std::move(channel)),
      instance_(randomInstance()),
      last_utime_(nowUtime()) {}

void StatusReporter::publish(int8_t state) {
  const int64_t now = nowUtime();
  const double seconds = std::max(1e-6, static_cast<double>(now - last_utime_) * 1e-6);
  process_status_t msg;
  msg.utime = now;
  msg.name = name_;
  msg.pid = static_cast<int32_t>(getpid());
  msg.instance = instance_;
  msg.state = state;
  msg.input_rate_hz = static_cast<float>(static_cast<double>(received_ - last_received_) / seconds);
  msg.output_rate_hz = static_cast<float>(static_cast<double>(published_ - last_published_) / seconds);
  msg.received = received_;
  msg.processed = processed_;
  msg.dropped = dropped_;
  msg.lost = lost_;
  msg.malformed = malformed_ + lcm_.malformedCount();
  msg.message = message_;
  lcm_.publish(channel_, msg);
  last_utime_ = now;
  last_received_ = received_;
  last_published_ = published_;
}

void StatusReporter::tick(bool force) {
  if (force || !announced_ || nowUtime() - last_utime_ >= 1000000) publish(process_status_t::STATE_RUNNING);
  announced_ = true;
}

void StatusReporter::finish() {
  publish(process_status_t::STATE_FINISHED);
}

void finishConfig(const ProcessContext& context) {
  context.config.finish();
  const std::vector<std::string> values = context.config.effectiveValues();
  if (context.args.flag("print-config")) {
    for (const auto& line : values) std::cout << line << "\n";
    std::cout << std::flush;
    throw ConfigPrinted();
  }
  for (const auto& line : values) log::info("  config ", line);
}

namespace {

// Frames and images are megabyte buffers, allocated and freed many times a second on several threads. glibc
// raises its mmap threshold each time such a buffer is freed, and from then on they come from the threads'
// heaps, whose fragments are not given back: the tracker's resident memory crept up about 2 MiB a minute in
// a real-time soak (+14 % from minute 5 to 10). A fixed threshold keeps them mapped and returned when freed
// (the same soak: +1 % from minute 5 to 7).
constexpr int kMmapThresholdBytes = 256 * 1024;

void keepLargeBuffersMapped() {
  if (mallopt(M_MMAP_THRESHOLD, kMmapThresholdBytes) != 1) log::warn("mallopt(M_MMAP_THRESHOLD) failed");
}

}  // namespace

int runProcess(int argc, char** argv, const ProcessSpec& spec) {
  keepLargeBuffersMapped();
  ArgParser args(spec.name, spec.summary);
  const std::string default_config =
      spec.default_config.empty() ? "" : configDir() + "/" + spec.default_config;
  args.addOption("config", "FILE", "YAML configuration", default_config);
  args.addOption("lcm-url", "URL",
                 "LCM provider URL; else $LCM_DEFAULT_URL, else " + std::string(kDefaultLcmUrl) +
                     " (a udpm URL without recv_buf_size gets the default size)");
  args.addFlag("print-config",
               "print every effective configuration value (options applied) and exit without starting");
  if (spec.add_options) spec.add_options(args);
  try {
    if (!args.parse(argc, argv)) {
      std::cout << args.help();
      return 0;
    }
  } catch (const ArgError& e) {
    std::cerr << e.what() << "\n";
    return 2;
  }

  try {
    const std::string config_path = args.value("config");
    Config config =
        config_path.empty() ? Config::empty("(no configuration file)") : Config::fromFile(config_path);
    const std::string url = resolveLcmUrl(args.value("lcm-url"));
    LcmNode lcm(url);
    StopSignal stop;
    StatusReporter status(lcm, spec.name);
    log::info(spec.name, " starting (pid ", getpid(), ", config ", config.origin(), ", LCM ", url, ")");
    ProcessContext context{args, config, lcm, stop, status};
    const int code = spec.run(context);
    status.finish();
    log::info(spec.name, " stopped",
              stop.signalNumber() > 0 ? " on signal " + std::to_string(stop.signalNumber()) : "",
              ", exit code ", code);
    return code;
  } catch (const ConfigPrinted&) {
    return 0;
  } catch (const ConfigError& e) {
    log::error(spec.name, ": configuration error: ", e.what());
    return 2;
  } catch (const ArgError& e) {
    log::error(e.what());
    return 2;
  } catch (const std::exception& e) {
    log::error(spec.name, ": ", e.what());
    return 1;
  }
}

}  // namespace bmp

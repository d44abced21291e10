// bmp-bench-tracker: runs the tracker over a TUM-format folder in lockstep and prints per-frame tracking
// time (median, p95), frames lost and the ATE against the folder's groundtruth.txt.
#include <iostream>
#include <string>

#include "bench_run.hpp"
#include "bmp/common/config.hpp"
#include "bmp/common/log.hpp"

namespace {
// The parser's own messages already start with the program's name; the run's checks do not all.
std::string usageLine(const bmp::ArgError& e) {
  const std::string what = e.what();
  const std::string prefix = "bmp-bench-tracker: ";
  return what.rfind(prefix, 0) == 0 ? what : prefix + what;
}
}  // namespace

int main(int argc, char** argv) {
  bmp::ArgParser args(
      "bmp-bench-tracker",
      "Tracks a TUM-format RGB-D folder frame by frame (no LCM) and reports tracking time per "
      "frame (median, p95), frames lost and ATE RMSE against groundtruth.txt.");
  bmp::tracker::addBenchTrackerOptions(args);
  try {
    if (!args.parse(argc, argv)) {
      std::cout << args.help();
      return 0;
    }
    if (!args.given("dataset")) throw bmp::ArgError("--dataset is required");
  } catch (const bmp::ArgError& e) {
    std::cerr << usageLine(e) << "\n" << args.help();
    return 2;
  }
  try {
    return bmp::tracker::runBenchTracker(args);
  } catch (const bmp::ArgError& e) {  // an option's value checked once the run reads it: still a usage error
    std::cerr << usageLine(e) << " (see --help)\n";
    return 2;
  } catch (const bmp::ConfigError& e) {
    bmp::log::error(e.what());
    return 2;
  } catch (const std::exception& e) {
    bmp::log::error(e.what());
    return 1;
  }
}

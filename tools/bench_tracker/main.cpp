// bmp-bench-tracker: runs the tracker over a TUM-format folder in lockstep and prints per-frame tracking
// time (median, p95), frames lost and the ATE against the folder's groundtruth.txt.
#include <iostream>

#include "bench_run.hpp"
#include "bmp/common/config.hpp"
#include "bmp/common/log.hpp"

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
    std::cerr << "bmp-bench-tracker: " << e.what() << "\n" << args.help();
    return 2;
  }
  try {
    return bmp::tracker::runBenchTracker(args);
  } catch (const bmp::ConfigError& e) {
    bmp::log::error(e.what());
    return 2;
  } catch (const std::exception& e) {
    bmp::log::error(e.what());
    return 1;
  }
}

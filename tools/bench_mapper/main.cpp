// bmp-bench-mapper: integration time per keyframe, map size and peak memory of the mapper library (no LCM).
#include "bench_run.hpp"
#include "bmp/common/tool_main.hpp"

int main(int argc, char** argv) {
  bmp::ArgParser args(
      "bmp-bench-mapper",
      "Integrates keyframes into the mapper library (no LCM) and prints integration time per keyframe "
      "(median, p95), map size and peak resident memory.");
  bmp::mapper::addBenchMapperOptions(args);
  return bmp::runTool(args, argc, argv, bmp::mapper::runBenchMapper);
}

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "eval/ate.hpp"
#include "eval/eval_error.hpp"
#include "eval/eval_plot.hpp"
#include "eval/plot_canvas.hpp"
#include "eval/rpe.hpp"
#include "eval_test_util.hpp"
#include "shared_data.hpp"

namespace bmp::eval {

namespace {
struct PngInfo {
  bool valid = false;
  std::uint32_t width = 0;
  std::uint32_t height = 0;
};

// Checks the signature and reads the IHDR chunk, which must come first.
PngInfo readPngHeader(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  unsigned char b[24] = {};
  in.read(reinterpret_cast<char*>(b), sizeof(b));
  PngInfo info;
  const unsigned char signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (!in || !std::equal(signature, signature + 8, b) || std::string(b + 12, b + 16) != "IHDR") return info;
  auto be32 = [&](int o) {
    return (std::uint32_t(b[o]) << 24) | (std::uint32_t(b[o + 1]) << 16) | (std::uint32_t(b[o + 2]) << 8) |
           std::uint32_t(b[o + 3]);
  };
  info = {true, be32(16), be32(20)};
  return info;
}
}  // namespace

TEST(evalPlot, NiceStepsAreOneTwoFive) {
  EXPECT_NEAR(niceStep(1.0, 10), 0.1, 1e-15);
  EXPECT_NEAR(niceStep(0.9, 4), 0.5, 1e-15);
  EXPECT_NEAR(niceStep(30.0, 6), 5.0, 1e-12);
  EXPECT_NEAR(niceStep(0.012, 5), 0.005, 1e-15);
}

TEST(evalPlot, WritesValidPngsOfPlausibleSize) {
  Trajectory gt;
  Trajectory est;
  for (int k = 0; k < 200; ++k) {
    const double s = 0.03 * k;
    gt.push_back({s, test::pose(std::cos(s), std::sin(2 * s), 0.1 * s, s)});
    est.push_back({s + 0.005, test::pose(std::cos(s) + 0.02 * std::sin(7 * s), std::sin(2 * s), 0.1 * s, s)});
  }
  const AteResult ate = computeAte(gt, est);
  const RpeResult rpe = computeRpe(gt, est);
  const auto dir = bmp::test::scratchDir("eval_plot");
  const std::string trajectory_png = (dir / "t.png").string();
  const std::string errors_png = (dir / "e.png").string();
  plotTrajectoryTopView(trajectory_png, gt, alignedTrajectory(est, ate.alignment, 1.0), ate, "test");
  plotErrorsOverTime(errors_png, ate, rpe, gt.front().stamp, "delta 1 s", "test");
  for (const auto& path : {trajectory_png, errors_png}) {
    const PngInfo info = readPngHeader(path);
    ASSERT_TRUE(info.valid) << path;
    EXPECT_GE(info.width, 800u);
    EXPECT_GE(info.height, 600u);
    const auto bytes = std::filesystem::file_size(path);
    EXPECT_GT(bytes, 10'000u) << path;  // a blank canvas compresses to a few kB
    EXPECT_LT(bytes, 3'000'000u) << path;
  }
}

TEST(evalPlot, UnwritablePathIsAnEvalError) {
  const AteResult ate;
  const RpeResult rpe;
  EXPECT_THROW(plotErrorsOverTime("/nonexistent-dir/x.png", ate, rpe, 0.0, "", ""), EvalError);
}

}  // namespace bmp::eval

// The packed window grid against the frame's own grid walk, on a real TUM frame's ORB keypoints: for any
// window, level range and subset, it returns exactly the keypoints Features::forEachInArea returns.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <limits>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <random>
#include <vector>

#include "shared_data.hpp"
#include "tracker/keypoint_window_grid.hpp"
#include "tracker/orb_extractor.hpp"

namespace bmp::tracker {
namespace {

struct RealFrame {
  CameraIntrinsics k;
  TrackerConfig config;
  FrameGeometry g{k, config};
  std::shared_ptr<const Features> f;
  RealFrame() {
    cv::Mat gray = cv::imread(test::sharedPath("images/tum_fr3_sitting_xyz_1341845839.214000.png"),
                              cv::IMREAD_GRAYSCALE);
    if (gray.empty()) return;
    cv::resize(gray, gray, cv::Size(640, 480));
    const OrbExtractor extractor(config.orb);
    f = buildFeatures(extractor.extract(gray), cv::Mat(), g, nullptr, cv::Mat());
  }
};

std::vector<int> sorted(std::vector<int> v) {
  std::sort(v.begin(), v.end());
  return v;
}

TEST(KeypointWindowGrid, FindsWhatTheFramesGridWalkFindsForAnyWindowLevelsAndSubset) {
  const RealFrame s;
  ASSERT_TRUE(s.f) << "image missing under " << test::sharedDir();
  const Features& f = *s.f;
  ASSERT_GT(f.size(), 500);
  std::mt19937 rng(7);
  // A subset, as the dynamic stage packs one: every third keypoint of the frame's grid.
  std::vector<int> all, subset;
  for (const auto& cell : f.grid)
    for (int i : cell) {
      all.push_back(i);
      if (i % 3 == 0) subset.push_back(i);
    }
  std::uniform_real_distribution<double> u(s.g.min_x - 20, s.g.max_x + 20), v(s.g.min_y - 20, s.g.max_y + 20);
  int found = 0;
  for (const double radius : {8.0, 24.0, 40.0, 60.0}) {
    const KeypointWindowGrid whole(f, s.g, radius, all), part(f, s.g, radius, subset);
    for (int q = 0; q < 300; ++q) {
      const double x = u(rng), y = v(rng);
      // Either bound may be open (-1), as a search at level 0 asks for levels [-1, 1].
      const int lo = static_cast<int>(rng() % 9) - 1;
      const int hi = rng() % 4 == 0 ? -1 : std::max(lo, 0) + static_cast<int>(rng() % 3);
      std::vector<int> expected, expected_part, got, got_part;
      f.forEachInArea(s.g, x, y, radius, lo, hi, [&](int i) {
        expected.push_back(i);
        if (i % 3 == 0) expected_part.push_back(i);
      });
      whole.forEach(x, y, radius, lo, hi, [&](int i) { got.push_back(i); });
      part.forEach(x, y, radius, lo, hi, [&](int i) { got_part.push_back(i); });
      ASSERT_EQ(sorted(got), sorted(expected)) << "window at " << x << ", " << y << " r " << radius;
      ASSERT_EQ(sorted(got_part), sorted(expected_part)) << "window at " << x << ", " << y << " r " << radius;
      found += static_cast<int>(expected.size());
    }
  }
  EXPECT_GT(found, 5000);  // the windows were not all empty
}

// A map point projected through a wild camera model can land anywhere, or nowhere: a search centred on a
// position that is not a number, infinite or far off finds nothing (its cell is chosen in double, never by
// casting such a value to int), and a window wider than the image finds every keypoint.
TEST(KeypointWindowGrid, AWindowCentredOnNoNumberOrFarOffFindsNothingAndAHugeOneFindsAll) {
  const RealFrame s;
  ASSERT_TRUE(s.f) << "image missing under " << test::sharedDir();
  const Features& f = *s.f;
  std::vector<int> all;
  for (const auto& cell : f.grid) all.insert(all.end(), cell.begin(), cell.end());
  ASSERT_GT(all.size(), 500u);
  const KeypointWindowGrid grid(f, s.g, 40.0, all);
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  const double cx = 0.5 * (s.g.min_x + s.g.max_x), cy = 0.5 * (s.g.min_y + s.g.max_y);
  const std::vector<std::array<double, 3>> nowhere = {{nan, cy, 40},  {cx, nan, 40},   {inf, cy, 40},
                                                      {cx, -inf, 40}, {1e300, cy, 40}, {cx, -1e300, 40},
                                                      {cx, cy, nan},  {cx, cy, -5},    {3e9, 3e9, 40}};
  for (const auto& [u, v, r] : nowhere) {
    int a = 0, b = 0;
    f.forEachInArea(s.g, u, v, r, [&](int) { ++a; });
    grid.forEach(u, v, r, -1, -1, [&](int) { ++b; });
    EXPECT_EQ(a, 0) << "frame grid, window at " << u << ", " << v << " r " << r;
    EXPECT_EQ(b, 0) << "window grid, window at " << u << ", " << v << " r " << r;
  }
  std::vector<int> got_frame, got_grid;
  f.forEachInArea(s.g, cx, cy, 1e300, [&](int i) { got_frame.push_back(i); });
  grid.forEach(cx, cy, 1e300, -1, -1, [&](int i) { got_grid.push_back(i); });
  EXPECT_EQ(sorted(got_frame), sorted(all));
  EXPECT_EQ(sorted(got_grid), sorted(all));
}

}  // namespace
}  // namespace bmp::tracker

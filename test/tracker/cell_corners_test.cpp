#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include <opencv2/features2d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "shared_data.hpp"
#include "tracker/cell_corners.hpp"

namespace bmp::tracker {
namespace {

// The definition: FAST at the weak threshold over the whole image; a cell with a strong corner keeps only
// its strong ones.
std::vector<cv::KeyPoint> wholeImageCorners(const cv::Mat& image, const CellCornerOptions& o) {
  std::vector<cv::KeyPoint> all;
  cv::FAST(image, all, o.min_threshold, true);
  const int w = image.cols, h = image.rows, cols = (w + o.cell - 1) / o.cell,
            rows = (h + o.cell - 1) / o.cell;
  std::vector<cv::KeyPoint> inside;
  std::vector<uint8_t> strong(static_cast<std::size_t>(cols * rows), 0);
  for (const auto& kp : all) {
    if (kp.pt.x < o.border || kp.pt.y < o.border || kp.pt.x >= w - o.border || kp.pt.y >= h - o.border)
      continue;
    inside.push_back(kp);
    if (kp.response >= o.threshold)
      strong[static_cast<int>(kp.pt.y) / o.cell * cols + static_cast<int>(kp.pt.x) / o.cell] = 1;
  }
  std::vector<cv::KeyPoint> kept;
  for (const auto& kp : inside)
    if (!strong[static_cast<int>(kp.pt.y) / o.cell * cols + static_cast<int>(kp.pt.x) / o.cell] ||
        kp.response >= o.threshold)
      kept.push_back(kp);
  return kept;
}

void expectSame(const std::vector<cv::KeyPoint>& got, const std::vector<cv::KeyPoint>& want,
                const std::string& what) {
  ASSERT_EQ(got.size(), want.size()) << what;
  for (std::size_t i = 0; i < got.size(); ++i) {
    ASSERT_EQ(got[i].pt, want[i].pt) << what << ", corner " << i;
    ASSERT_EQ(got[i].response, want[i].response) << what << ", corner " << i;
  }
}

// Real frames (a TUM frame and Bonn crowd frames, each at several pyramid sizes, with texture-poor walls and
// textured people): the cell runs give exactly the whole-image run's corners, in its order.
TEST(TrackerCellCorners, SameCornersAsTheWholeImageRunOnRealFrames) {
  std::vector<std::string> files = {test::sharedPath("images/tum_fr3_sitting_xyz_1341845839.214000.png")};
  const std::string rgb = test::bonnDir() + "/rgb";
  std::vector<std::string> bonn;
  for (const auto& e : std::filesystem::directory_iterator(rgb)) bonn.push_back(e.path().string());
  ASSERT_GE(bonn.size(), 100u) << rgb;
  std::sort(bonn.begin(), bonn.end());
  files.push_back(bonn[0]);
  files.push_back(bonn[bonn.size() / 2]);
  const CellCornerOptions options{19, 30, 20, 7};
  std::size_t weak_corners = 0;
  for (const auto& file : files) {
    cv::Mat image = cv::imread(file, cv::IMREAD_GRAYSCALE);
    ASSERT_FALSE(image.empty()) << file;
    for (int level = 0; level < 4; ++level) {
      const auto want = wholeImageCorners(image, options);
      const auto got = cellCorners(image, options);
      expectSame(got, want, file + " level " + std::to_string(level));
      for (const auto& kp : got) weak_corners += kp.response < options.threshold;
      cv::resize(image, image, cv::Size(), 1 / 1.2, 1 / 1.2, cv::INTER_LINEAR);
    }
  }
  // The weak threshold did its part: the comparison covered weak cells' corners, not only strong ones.
  EXPECT_GT(weak_corners, 50u);
}

// Corner cases: a flat image (every cell weak, no corner at all), a strong threshold no weaker than the weak
// one (one run), and cells cut by the image edge (a size that is no multiple of the cell).
TEST(TrackerCellCorners, SameCornersOnFlatImagesOddSizesAndEqualThresholds) {
  cv::Mat flat(97, 131, CV_8UC1, cv::Scalar(90));
  EXPECT_TRUE(cellCorners(flat, {5, 30, 20, 7}).empty());
  cv::Mat noise(97, 131, CV_8UC1);
  cv::RNG rng(3);
  rng.fill(noise, cv::RNG::UNIFORM, 0, 255);
  cv::GaussianBlur(noise, noise, cv::Size(5, 5), 1.2);
  // Half the image flat, so there are both strong and weak cells.
  noise(cv::Rect(0, 0, 65, 97)) *= 0.08;
  for (const CellCornerOptions& o : {CellCornerOptions{5, 30, 20, 7}, CellCornerOptions{0, 17, 12, 3},
                                     CellCornerOptions{9, 30, 10, 10}, CellCornerOptions{9, 30, 7, 12}}) {
    const auto want = wholeImageCorners(noise, o);
    ASSERT_FALSE(want.empty());
    expectSame(cellCorners(noise, o), want, "cell " + std::to_string(o.cell));
  }
}

}  // namespace
}  // namespace bmp::tracker

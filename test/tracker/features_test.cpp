// Per-keypoint data: depth from 16-bit or float images, and the exclusion hook (weight callback and mask).
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "tracker/frame.hpp"

namespace bmp::tracker {
namespace {

cv::Mat shapes() {
  cv::Mat img(480, 640, CV_8UC1, cv::Scalar(100));
  cv::RNG rng(5);
  for (int i = 0; i < 300; ++i) {
    const cv::Point c(rng.uniform(0, 640), rng.uniform(0, 480));
    cv::rectangle(img, c, c + cv::Point(rng.uniform(6, 30), rng.uniform(6, 30)),
                  cv::Scalar(rng.uniform(0, 255)), cv::FILLED);
  }
  return img;
}

TEST(TrackerFeatures, DepthFromRawOrMetresAndExclusionHook) {
  CameraIntrinsics k;  // 525, 319.5, 239.5, no distortion, depth_scale 5000
  const TrackerConfig config;
  const FrameGeometry g(k, config);
  const OrbExtractor extractor(config.orb);
  const OrbFeatures orb = extractor.extract(shapes());
  ASSERT_GT(orb.keys.size(), 500u);

  // Depth grows with x; the left quarter has none.
  cv::Mat raw(480, 640, CV_16UC1), metres(480, 640, CV_32FC1);
  for (int y = 0; y < 480; ++y)
    for (int x = 0; x < 640; ++x) {
      const double d = x < 160 ? 0.0 : 1.0 + x / 640.0;
      raw.at<uint16_t>(y, x) = static_cast<uint16_t>(d * 5000.0);
      metres.at<float>(y, x) = static_cast<float>(d);
    }
  const auto a = buildFeatures(orb, raw, g, nullptr, cv::Mat());
  const auto b = buildFeatures(orb, metres, g, nullptr, cv::Mat());
  ASSERT_EQ(a->size(), b->size());
  for (int i = 0; i < a->size(); ++i) {
    EXPECT_NEAR(a->depth[i], b->depth[i], 1e-3);
    if (a->keys[i].pt.x < 159.0f) {
      EXPECT_FALSE(a->hasDepth(i));
    } else if (a->keys[i].pt.x > 161.0f) {
      EXPECT_NEAR(a->depth[i], 1.0 + cvRound(a->keys[i].pt.x) / 640.0, 1e-3);
    }
    EXPECT_EQ(a->excluded[i], 0);
  }

  // The hook: the weight callback excludes the top half (weight 0), the mask the right quarter.
  cv::Mat mask = cv::Mat::zeros(480, 640, CV_8UC1);
  mask.colRange(480, 640).setTo(255);
  const auto c = buildFeatures(
      orb, raw, g, [](const cv::KeyPoint& kp, float) { return kp.pt.y < 240.0f ? 0.0f : 0.5f; }, mask);
  int in_grid = 0;
  for (const auto& cell : c->grid) in_grid += static_cast<int>(cell.size());
  int usable = 0;
  for (int i = 0; i < c->size(); ++i) {
    const auto& pt = c->keys[i].pt;
    const bool expect_excluded = cvRound(pt.y) < 240 || cvRound(pt.x) >= 480;
    EXPECT_EQ(c->excluded[i] != 0, expect_excluded) << pt;
    if (!expect_excluded) {
      EXPECT_FLOAT_EQ(c->weight[i], 0.5f);
      ++usable;
    }
  }
  EXPECT_GT(usable, 50);
  EXPECT_EQ(in_grid, usable);  // excluded keypoints cannot be matched: they are not in the search grid
  EXPECT_EQ(c->numExcluded(), c->size() - usable);
}

// A keypoint whose position is not a number (a wild distortion model undistorts it to nowhere) fits no
// cell of the frame's grid, so no search can return it; the keypoints beside it keep theirs.
TEST(TrackerFeatures, AKeypointThatIsNotANumberFitsNoCell) {
  const CameraIntrinsics k;
  const TrackerConfig config;
  const FrameGeometry g(k, config);
  OrbFeatures orb;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (const cv::Point2f pt : {cv::Point2f(100, 100), cv::Point2f(nan, 100), cv::Point2f(300, nan),
                               cv::Point2f(1e30f, 200), cv::Point2f(320, 240)})
    orb.keys.emplace_back(pt, 31.0f);
  orb.descriptors = cv::Mat::zeros(static_cast<int>(orb.keys.size()), 32, CV_8U);
  const auto f = buildFeatures(orb, cv::Mat(), g, nullptr, cv::Mat());
  std::vector<int> in_grid;
  for (const auto& cell : f->grid) in_grid.insert(in_grid.end(), cell.begin(), cell.end());
  std::sort(in_grid.begin(), in_grid.end());
  EXPECT_EQ(in_grid, (std::vector<int>{0, 4}));
  for (int i = 0; i < f->size(); ++i) EXPECT_FALSE(f->hasDepth(i)) << "keypoint " << i;
}

}  // namespace
}  // namespace bmp::tracker

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "shared_data.hpp"
#include "tracker/orb_extractor.hpp"

namespace bmp::tracker {
namespace {

cv::Mat texturedImage(int seed) {
  cv::Mat img(480, 640, CV_8UC1);
  cv::RNG rng(seed);
  rng.fill(img, cv::RNG::UNIFORM, 0, 255);
  cv::GaussianBlur(img, img, cv::Size(5, 5), 1.5);
  return img;
}

TEST(TrackerOrbExtractor, ExtractsAboutTheRequestedNumberSpreadOverTheImage) {
  OrbOptions options;
  const OrbExtractor extractor(options);
  const OrbFeatures f = extractor.extract(texturedImage(1));
  ASSERT_EQ(static_cast<int>(f.keys.size()), f.descriptors.rows);
  EXPECT_GE(f.keys.size(), 900u);
  EXPECT_LE(f.keys.size(), 1000u);
  // Every quadrant holds a fair share: the distribution is even, not just the strongest corners.
  int quadrant[4] = {0, 0, 0, 0};
  int levels_used[8] = {0};
  for (const auto& k : f.keys) {
    quadrant[(k.pt.x >= 320) + 2 * (k.pt.y >= 240)]++;
    ASSERT_GE(k.octave, 0);
    ASSERT_LT(k.octave, 8);
    levels_used[k.octave]++;
  }
  for (int q : quadrant) EXPECT_GT(q, static_cast<int>(f.keys.size()) / 6);
  for (int l = 0; l < 8; ++l) EXPECT_GT(levels_used[l], 0) << "level " << l;
}

// Random shapes: corners that FAST finds again after a rotation, unlike pixel noise.
cv::Mat shapesImage(int seed) {
  cv::Mat img(480, 640, CV_8UC1, cv::Scalar(128));
  cv::RNG rng(seed);
  for (int i = 0; i < 400; ++i) {
    const cv::Point c(rng.uniform(0, 640), rng.uniform(0, 480));
    const int grey = rng.uniform(0, 255);
    if (i % 2 == 0)
      cv::rectangle(img, c, c + cv::Point(rng.uniform(8, 40), rng.uniform(8, 40)), cv::Scalar(grey),
                    cv::FILLED);
    else
      cv::circle(img, c, rng.uniform(4, 20), cv::Scalar(grey), cv::FILLED);
  }
  cv::GaussianBlur(img, img, cv::Size(3, 3), 0.8);
  return img;
}

TEST(TrackerOrbExtractor, DescriptorsMatchUnderRotation) {
  const OrbExtractor extractor(OrbOptions{});
  const cv::Mat img = shapesImage(2);
  cv::Mat rotated;
  const cv::Mat R = cv::getRotationMatrix2D(cv::Point2f(320, 240), 30.0, 1.0);
  cv::warpAffine(img, rotated, R, img.size());
  const OrbFeatures a = extractor.extract(img);
  const OrbFeatures b = extractor.extract(rotated);
  // Keypoints near the centre survive the rotation; their nearest rotated keypoint should match.
  int tested = 0, matched = 0;
  for (std::size_t i = 0; i < a.keys.size(); ++i) {
    const auto& k = a.keys[i];
    if (k.octave != 0 || std::hypot(k.pt.x - 320, k.pt.y - 240) > 150) continue;
    const cv::Point2f p(
        static_cast<float>(R.at<double>(0, 0) * k.pt.x + R.at<double>(0, 1) * k.pt.y + R.at<double>(0, 2)),
        static_cast<float>(R.at<double>(1, 0) * k.pt.x + R.at<double>(1, 1) * k.pt.y + R.at<double>(1, 2)));
    int best = -1;
    double best_d = 2.0;
    for (std::size_t j = 0; j < b.keys.size(); ++j) {
      const double d = cv::norm(b.keys[j].pt - p);
      if (b.keys[j].octave == 0 && d < best_d) {
        best_d = d;
        best = static_cast<int>(j);
      }
    }
    if (best < 0) continue;
    ++tested;
    matched +=
        hamming(a.descriptors.ptr<uint8_t>(static_cast<int>(i)), b.descriptors.ptr<uint8_t>(best)) < 64;
  }
  ASSERT_GT(tested, 30);
  EXPECT_GT(matched, tested * 7 / 10) << matched << " of " << tested;
}

// A real TUM frame with people; the middle half of the image stands for a person's box.
TEST(TrackerOrbExtractor, SparseBoxesGiveTheirBudgetToTheRestOfTheImage) {
  cv::Mat gray =
      cv::imread(test::sharedPath("images/tum_fr3_sitting_xyz_1341845839.214000.png"), cv::IMREAD_GRAYSCALE);
  ASSERT_FALSE(gray.empty()) << "image missing under " << test::sharedDir();
  cv::resize(gray, gray, cv::Size(640, 480));
  const OrbExtractor extractor{OrbOptions{}};
  const cv::Rect2f box(160, 0, 320, 480);
  auto count = [&](const OrbFeatures& f) {
    std::pair<int, int> in_out{0, 0};
    for (const auto& k : f.keys) (box.contains(k.pt) ? in_out.first : in_out.second)++;
    return in_out;
  };
  const OrbFeatures plain = extractor.extract(gray);
  const OrbFeatures quarter = extractor.extract(gray, SparseRegions{{box}, 0.25});
  const OrbFeatures none = extractor.extract(gray, SparseRegions{{box}, 0.0});
  const auto [plain_in, plain_out] = count(plain);
  const auto [quarter_in, quarter_out] = count(quarter);
  const auto [none_in, none_out] = count(none);
  ASSERT_GT(plain_in, 300);
  ASSERT_GT(plain_out, 300);
  // The budget is kept, and moves out of the box: at share 0.25 a half-image box gets about a fifth.
  EXPECT_NEAR(static_cast<double>(quarter.keys.size()), static_cast<double>(plain.keys.size()), 10.0);
  EXPECT_EQ(quarter.keys.size(), static_cast<std::size_t>(quarter.descriptors.rows));
  EXPECT_LT(quarter_in, plain_in * 6 / 10) << quarter_in << " of " << quarter.keys.size();
  EXPECT_GT(quarter_in, plain_in / 10) << "the box keeps some keypoints at share 0.25";
  EXPECT_GT(quarter_out, plain_out * 13 / 10);
  // Share 0: only bucket edges (centre outside the box) still reach into it.
  EXPECT_LT(none_in, quarter_in);
  EXPECT_GE(none_out, quarter_out);
  // Share 1, or no boxes, is the plain spread, keypoint for keypoint.
  const OrbFeatures one = extractor.extract(gray, SparseRegions{{box}, 1.0});
  ASSERT_EQ(one.keys.size(), plain.keys.size());
  for (std::size_t i = 0; i < one.keys.size(); ++i) ASSERT_EQ(one.keys[i].pt, plain.keys[i].pt) << i;
}

}  // namespace
}  // namespace bmp::tracker

#include <gtest/gtest.h>

#include "detector/letterbox.hpp"
#include "detector/yolo_decode.hpp"

namespace bmp::detector {
namespace {

TEST(DetectorLetterbox, LandscapeIsScaledAndPaddedTopAndBottom) {
  cv::Mat image(480, 640, CV_8UC3, cv::Scalar(10, 20, 30));
  cv::Mat square;
  const LetterboxTransform t = letterbox(image, 320, square);
  EXPECT_EQ(square.size(), cv::Size(320, 320));
  EXPECT_FLOAT_EQ(t.scale, 0.5f);
  EXPECT_EQ(t.pad_x, 0);
  EXPECT_EQ(t.pad_y, 40);
  EXPECT_EQ(square.at<cv::Vec3b>(0, 0), cv::Vec3b(114, 114, 114));
  EXPECT_EQ(square.at<cv::Vec3b>(319, 319), cv::Vec3b(114, 114, 114));
  EXPECT_EQ(square.at<cv::Vec3b>(160, 160), cv::Vec3b(10, 20, 30));
  const cv::Rect2f back = t.toImage(cv::Rect2f(100, 90, 50, 20));
  EXPECT_FLOAT_EQ(back.x, 200);
  EXPECT_FLOAT_EQ(back.y, 100);
  EXPECT_FLOAT_EQ(back.width, 100);
  EXPECT_FLOAT_EQ(back.height, 40);
}

TEST(DetectorLetterbox, PortraitIsPaddedLeftAndRight) {
  cv::Mat image(1080, 810, CV_8UC3, cv::Scalar::all(0));
  cv::Mat square;
  const LetterboxTransform t = letterbox(image, 640, square);
  EXPECT_NEAR(t.scale, 640.0f / 1080.0f, 1e-6);
  EXPECT_EQ(t.pad_y, 0);
  EXPECT_EQ(t.pad_x, (640 - 480) / 2);
  EXPECT_EQ(square.at<cv::Vec3b>(320, 10), cv::Vec3b(114, 114, 114));
  EXPECT_EQ(square.at<cv::Vec3b>(320, 320), cv::Vec3b(0, 0, 0));
}

TEST(DetectorLetterbox, SquareImageOfInputSizeIsCopied) {
  cv::Mat image(320, 320, CV_8UC3);
  cv::randu(image, 0, 255);
  cv::Mat square;
  const LetterboxTransform t = letterbox(image, 320, square);
  EXPECT_FLOAT_EQ(t.scale, 1.0f);
  EXPECT_EQ(cv::norm(image, square, cv::NORM_INF), 0.0);
}

TEST(DetectorLetterbox, RejectsEmptyOrGreyImage) {
  cv::Mat square;
  EXPECT_THROW(letterbox(cv::Mat(), 320, square), std::invalid_argument);
  EXPECT_THROW(letterbox(cv::Mat(10, 10, CV_8UC1), 320, square), std::invalid_argument);
}

TEST(DetectorNms, IouOfKnownBoxes) {
  EXPECT_FLOAT_EQ(iou({0, 0, 10, 10}, {0, 0, 10, 10}), 1.0f);
  EXPECT_FLOAT_EQ(iou({0, 0, 10, 10}, {20, 20, 5, 5}), 0.0f);
  EXPECT_NEAR(iou({0, 0, 10, 10}, {5, 0, 10, 10}), 50.0f / 150.0f, 1e-6);
}

TEST(DetectorNms, SuppressesWithinAClassOnly) {
  std::vector<Candidate> in = {
      {{0, 0, 100, 100}, 0, 0.6f},   // person, overlaps the better person below
      {{5, 5, 100, 100}, 0, 0.9f},   // person, best
      {{5, 5, 100, 100}, 56, 0.5f},  // chair at the same place: other class, kept
      {{300, 300, 50, 50}, 0, 0.4f}  // person elsewhere, kept
  };
  const auto out = nmsPerClass(in, 0.45f, 100);
  ASSERT_EQ(out.size(), 3u);
  EXPECT_FLOAT_EQ(out[0].score, 0.9f);
  EXPECT_EQ(out[1].class_id, 56);
  EXPECT_FLOAT_EQ(out[2].score, 0.4f);
  EXPECT_EQ(nmsPerClass(in, 0.45f, 1).size(), 1u);
  // A threshold above their overlap keeps both persons.
  EXPECT_EQ(nmsPerClass(in, 0.95f, 100).size(), 4u);
}

cv::Mat rowsOf(const std::vector<std::vector<float>>& rows) {
  cv::Mat m(static_cast<int>(rows.size()), 85, CV_32F, cv::Scalar(0));
  for (int r = 0; r < m.rows; ++r)
    for (std::size_t c = 0; c < rows[r].size(); ++c) m.at<float>(r, static_cast<int>(c)) = rows[r][c];
  return m;
}

TEST(DetectorDecode, Yolov5ConfidenceIsObjectnessTimesClass) {
  cv::Mat rows = rowsOf({{100, 50, 20, 40, 0.8f}, {10, 10, 4, 4, 0.2f}, {200, 200, 10, 10, 0.9f}});
  rows.at<float>(0, 5 + 0) = 0.9f;   // person: 0.72
  rows.at<float>(0, 5 + 56) = 0.1f;  // chair, not the best class
  rows.at<float>(1, 5 + 0) = 1.0f;   // objectness 0.2 < threshold
  rows.at<float>(2, 5 + 62) = 0.2f;  // 0.18 < threshold
  const auto out = decodeRows(rows, ScoreLayout::kObjectnessTimesClass, 1.0f, 0.25f);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].class_id, 0);
  EXPECT_NEAR(out[0].score, 0.72f, 1e-6);
  EXPECT_FLOAT_EQ(out[0].box.x, 90);
  EXPECT_FLOAT_EQ(out[0].box.y, 30);
  EXPECT_FLOAT_EQ(out[0].box.width, 20);
  EXPECT_FLOAT_EQ(out[0].box.height, 40);
}

TEST(DetectorDecode, DarknetScoresAndNormalisedBoxes) {
  cv::Mat rows = rowsOf({{0.5f, 0.25f, 0.1f, 0.2f, 0.7f}});
  rows.at<float>(0, 5 + 2) = 0.6f;  // already objectness x class
  const auto out = decodeRows(rows, ScoreLayout::kClassIncludesObjectness, 320.0f, 0.25f);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].class_id, 2);
  EXPECT_FLOAT_EQ(out[0].score, 0.6f);
  EXPECT_FLOAT_EQ(out[0].box.x, 160 - 16);
  EXPECT_FLOAT_EQ(out[0].box.y, 80 - 32);
}

}  // namespace
}  // namespace bmp::detector

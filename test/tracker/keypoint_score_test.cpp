#include <gtest/gtest.h>

#include "tracker_offline/keypoint_score.hpp"

namespace bmp::tracker {
namespace {

// A mover in the left half of a 20 x 10 image; keypoints on it and beside it, some kept out.
TEST(KeypointScore, CountsKeypointsOnMoversAndOnTheStaticSceneAgainstTheMask) {
  cv::Mat movers = cv::Mat::zeros(10, 20, CV_8UC1);
  movers(cv::Rect(0, 0, 10, 10)).setTo(255);
  TrackResult r;
  const auto add = [&r](float x, float y, bool out) {
    r.keypoints.emplace_back(x, y);
    r.keypoint_dynamic.push_back(out ? 1 : 0);
  };
  add(1, 1, true), add(2, 5, true), add(9.4F, 9, true), add(5, 5, false);                    // on the mover
  add(10, 1, true), add(12, 5, false), add(15, 5, false), add(19, 9, false), add(11, 0, false),  // static
  add(18, 3, false);
  add(25, 5, true), add(-1, 3, true);  // outside the image: not counted
  KeypointScore score;
  score.add(r, movers);
  EXPECT_EQ(score.onMovers(), 4);
  EXPECT_EQ(score.onStatic(), 6);
  EXPECT_EQ(score.flagged(), 4);
  EXPECT_DOUBLE_EQ(score.precision(), 3.0 / 4.0);
  EXPECT_DOUBLE_EQ(score.recall(), 3.0 / 4.0);
  EXPECT_DOUBLE_EQ(score.staticKeptOut(), 1.0 / 6.0);
  score.add(r, movers);  // counts add up over frames
  EXPECT_EQ(score.onMovers(), 8);
  EXPECT_DOUBLE_EQ(score.recall(), 3.0 / 4.0);
}

TEST(KeypointScore, NothingKeptOutAndNoMoverGiveOneNotNaN) {
  KeypointScore score;
  EXPECT_DOUBLE_EQ(score.precision(), 1.0);
  EXPECT_DOUBLE_EQ(score.recall(), 1.0);
  EXPECT_DOUBLE_EQ(score.staticKeptOut(), 1.0);
}

TEST(KeypointScore, RejectsAMaskOfTheWrongTypeAndFlagsThatDoNotMatch) {
  KeypointScore score;
  TrackResult r;
  r.keypoints.emplace_back(1, 1);
  EXPECT_THROW(score.add(r, cv::Mat::zeros(4, 4, CV_8UC1)), std::invalid_argument);
  r.keypoint_dynamic.push_back(0);
  EXPECT_THROW(score.add(r, cv::Mat::zeros(4, 4, CV_16UC1)), std::invalid_argument);
}

}  // namespace
}  // namespace bmp::tracker

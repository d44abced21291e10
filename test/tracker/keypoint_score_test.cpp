#include <gtest/gtest.h>

#include "tracker_offline/keypoint_score.hpp"

namespace bmp::tracker {
namespace {

// A mover in the left half of a 20 x 10 image; keypoints on it and beside it, some kept out.
TEST(KeypointScore, CountsKeypointsOnMoversAndOnTheStaticSceneAgainstTheMask) {
  cv::Mat movers = cv::Mat::zeros(10, 20, CV_8UC1);
  movers(cv::Rect(0, 0, 10, 10)).setTo(255);
  TrackResult r;
  const auto add = [&r](float x, float y, bool out, bool in_region) {
    r.keypoints.emplace_back(x, y);
    r.keypoint_dynamic.push_back(out ? 1 : 0);
    r.keypoint_in_region.push_back(in_region ? 1 : 0);
  };
  add(1, 1, true, true), add(2, 5, true, false), add(9.4F, 9, true, true), add(5, 5, false, true);  // mover
  add(10, 1, true, true), add(12, 5, false, true), add(15, 5, false, false), add(19, 9, false, false),
      add(11, 0, false, false), add(18, 3, false, false);  // static
  add(25, 5, true, true), add(-1, 3, true, true);          // outside the image: not counted
  KeypointScore score;
  score.add(r, movers);
  EXPECT_EQ(score.onMovers(), 4);
  EXPECT_EQ(score.onStatic(), 6);
  EXPECT_EQ(score.flagged(), 4);
  EXPECT_DOUBLE_EQ(score.precision().value_or(-1), 3.0 / 4.0);
  EXPECT_DOUBLE_EQ(score.recall().value_or(-1), 3.0 / 4.0);
  EXPECT_DOUBLE_EQ(score.staticKeptOut().value_or(-1), 1.0 / 6.0);
  EXPECT_EQ(score.missedOutsideRegions(), 0);
  EXPECT_EQ(score.missedInsideRegions(), 1);  // (5, 5): its region said moving, its history held it
  EXPECT_EQ(score.staticOutInsideRegions(), 1);
  EXPECT_EQ(score.staticOutByHistory(), 0);
  r.keypoint_in_region.clear();  // a frame without boxes: every miss is outside the regions
  KeypointScore without;
  without.add(r, movers);
  EXPECT_EQ(without.missedOutsideRegions(), 1);
  EXPECT_EQ(without.staticOutByHistory(), 1);
  score.add(r, movers);  // counts add up over frames
  EXPECT_EQ(score.onMovers(), 8);
  EXPECT_DOUBLE_EQ(score.recall().value_or(-1), 3.0 / 4.0);
  EXPECT_EQ(score.missedOutsideRegions(), 1);
}

// Nothing scored is no score: a perfect 1.0 here once put 100 % into tools/bench's table for 5 frames.
TEST(KeypointScore, NothingCountedGivesNoShareNotAPerfectOne) {
  KeypointScore score;
  EXPECT_FALSE(score.precision().has_value());
  EXPECT_FALSE(score.recall().has_value());
  EXPECT_FALSE(score.staticKeptOut().has_value());
  EXPECT_FALSE(score.moversInPoseShare().has_value());
  EXPECT_EQ(shareText(score.recall()), "n/a");
  EXPECT_EQ(shareText(0.5), "0.5000");
  // Static keypoints only, none kept out: no mover to score recall on, nothing kept out for precision.
  TrackResult r;
  r.keypoints.emplace_back(1, 1);
  r.keypoint_dynamic.push_back(0);
  score.add(r, cv::Mat::zeros(4, 4, CV_8UC1));
  EXPECT_FALSE(score.recall().has_value());
  EXPECT_FALSE(score.precision().has_value());
  ASSERT_TRUE(score.staticKeptOut().has_value());
  EXPECT_DOUBLE_EQ(*score.staticKeptOut(), 0.0);
}

TEST(KeypointScore, RejectsAMaskOfTheWrongTypeAndFlagsThatDoNotMatch) {
  KeypointScore score;
  TrackResult r;
  r.keypoints.emplace_back(1, 1);
  EXPECT_THROW(score.add(r, cv::Mat::zeros(4, 4, CV_8UC1)), std::invalid_argument);
  r.keypoint_dynamic.push_back(0);
  EXPECT_THROW(score.add(r, cv::Mat::zeros(4, 4, CV_16UC1)), std::invalid_argument);
}

// The keyframes' masks pixel by pixel: a 20 x 10 image, the mover its left half (100 pixels), the mask
// 60 of them and 10 of the static half; a second keyframe with no mover and nothing masked.
TEST(MaskPixelScore, SharesOfTheMoversAndOfTheStaticScenePixelsMasked) {
  cv::Mat movers = cv::Mat::zeros(10, 20, CV_8UC1), mask = movers.clone();
  movers(cv::Rect(0, 0, 10, 10)).setTo(255);
  mask(cv::Rect(4, 0, 7, 10)).setTo(255);  // 6 columns on the mover, 1 beside it
  MaskPixelScore score;
  EXPECT_FALSE(score.moversMasked().has_value());
  score.add(mask, movers);
  score.add(cv::Mat::zeros(10, 20, CV_8UC1), cv::Mat::zeros(10, 20, CV_8UC1));
  EXPECT_EQ(score.keyframes(), 2);
  EXPECT_DOUBLE_EQ(score.moversMasked().value_or(-1), 60.0 / 100.0);
  EXPECT_DOUBLE_EQ(score.staticMasked().value_or(-1), 10.0 / 300.0);
  EXPECT_THROW(score.add(mask, cv::Mat::zeros(10, 21, CV_8UC1)), std::invalid_argument);
  EXPECT_THROW(score.add(cv::Mat::zeros(10, 20, CV_16UC1), movers), std::invalid_argument);
}

}  // namespace
}  // namespace bmp::tracker

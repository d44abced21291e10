// The paper's dynamic-region test and Bayesian moving probability, against hand-computed values.
#include <gtest/gtest.h>

#include "tracker/dynamic_regions.hpp"
#include "tracker/moving_probability.hpp"
#include "tracker/stand_in_boxes.hpp"

namespace bmp::tracker {
namespace {

constexpr double kEps = 1e-12;

TEST(MovingProbability, BothObservationsFollowBayes) {
  const MovingProbabilityOptions o;  // lambda = omega = 0.9
  EXPECT_NEAR(updateMovingProbability(0.5, true, o), 0.9, kEps);
  EXPECT_NEAR(updateMovingProbability(0.5, false, o), 0.1, kEps);
  // z = d from 0.3: 0.9*0.3 / (0.9*0.3 + 0.1*0.7) = 0.27 / 0.34
  EXPECT_NEAR(updateMovingProbability(0.3, true, o), 0.27 / 0.34, kEps);
  // z = s from 0.3: 0.1*0.3 / (0.1*0.3 + 0.9*0.7) = 0.03 / 0.66 (the paper's printed form would give
  // 0.27/0.34)
  EXPECT_NEAR(updateMovingProbability(0.3, false, o), 0.03 / 0.66, kEps);
  MovingProbabilityOptions asym;
  asym.lambda = 0.8;
  asym.omega = 0.6;
  // z = d: 0.8*0.5 / (0.8*0.5 + 0.4*0.5); z = s: 0.2*0.5 / (0.2*0.5 + 0.6*0.5)
  EXPECT_NEAR(updateMovingProbability(0.5, true, asym), 0.4 / 0.6, kEps);
  EXPECT_NEAR(updateMovingProbability(0.5, false, asym), 0.1 / 0.4, kEps);
}

TEST(MovingProbability, PropagatesOverFramesAndCrossesTheThreshold) {
  const MovingProbabilityOptions o;
  double p = o.unmatched_prior;
  p = updateMovingProbability(p, true, o);  // 0.9
  EXPECT_TRUE(isDynamic(p, o));
  p = updateMovingProbability(p, true, o);  // 0.81 / 0.82
  EXPECT_NEAR(p, 0.81 / 0.82, kEps);
  // Static observations bring it back: one returns to 0.9, two to 0.5 (not above the threshold), three below.
  p = updateMovingProbability(p, false, o);
  EXPECT_NEAR(p, 0.9, 1e-9);
  p = updateMovingProbability(p, false, o);
  EXPECT_NEAR(p, 0.5, 1e-9);
  EXPECT_FALSE(isDynamic(p, o));
  p = updateMovingProbability(p, false, o);
  EXPECT_NEAR(p, 0.1, 1e-9);
  // Certainty stays certain; out-of-range priors are clamped.
  EXPECT_EQ(updateMovingProbability(1.0, false, o), 1.0);
  EXPECT_EQ(updateMovingProbability(0.0, true, o), 0.0);
  EXPECT_EQ(updateMovingProbability(1.5, true, o), 1.0);
}

// A frame observed with stand-in boxes takes its own answer later in their place: withdrawing an
// observation undoes its update exactly, so the frame counts once.
TEST(MovingProbability, AWithdrawnObservationUndoesItsUpdate) {
  MovingProbabilityOptions o;
  for (const double lambda : {0.9, 0.7})
    for (const double p : {0.001, 0.1, 0.5, 0.83, 0.999})
      for (const bool z : {true, false}) {
        o.lambda = lambda;
        EXPECT_NEAR(withdrawObservation(updateMovingProbability(p, z, o), z, o), p, 1e-12);
      }
  // A stand-in said d (0.5 -> 0.9); the real answer says s: withdrawn and applied, 0.1, as if the frame
  // had had its own answer; applied on top, 0.5.
  o = {};
  const double stand_in = updateMovingProbability(0.5, true, o);
  EXPECT_NEAR(updateMovingProbability(withdrawObservation(stand_in, true, o), false, o), 0.1, 1e-12);
  EXPECT_NEAR(updateMovingProbability(stand_in, false, o), 0.5, 1e-12);
}

cv::KeyPoint at(float x, float y) {
  return cv::KeyPoint(cv::Point2f(x, y), 7.0f);
}

ObjectBox box(float x, float y, float w, float h, DynamicLevel level) {
  ObjectBox b;
  b.box = cv::Rect2f(x, y, w, h);
  b.level = level;
  return b;
}

TEST(DynamicRegions, InsideAPersonAndOutsideEveryLowBox) {
  const std::vector<ObjectBox> boxes = {box(100, 100, 200, 300, DynamicLevel::kHigh),
                                        box(150, 150, 50, 50, DynamicLevel::kLow)};  // monitor behind someone
  const std::vector<cv::KeyPoint> keys = {at(120, 120), at(160, 160), at(50, 50), at(299, 399), at(300, 400)};
  const auto moving = movingBoxes(boxes, RegionOptions{});
  const auto z = observeRegions(keys, boxes, moving);
  EXPECT_EQ(z, (std::vector<uint8_t>{1, 0, 0, 1, 0}));  // right and bottom edges are outside
}

TEST(DynamicRegions, OverlappingPeopleAndMediumObjects) {
  const std::vector<ObjectBox> boxes = {
      box(0, 0, 100, 100, DynamicLevel::kHigh), box(80, 0, 100, 100, DynamicLevel::kHigh),  // two people
      box(60, 40, 20, 20, DynamicLevel::kMedium),    // a cup in a person's hands: held, moves
      box(400, 300, 80, 80, DynamicLevel::kMedium),  // a chair alone: no evidence it moves
      box(90, 10, 20, 20, DynamicLevel::kLow)};      // a low object where the two people overlap
  const auto moving = movingBoxes(boxes, RegionOptions{});
  EXPECT_EQ(moving, (std::vector<uint8_t>{1, 1, 1, 0, 0}));
  const std::vector<cv::KeyPoint> keys = {at(85, 50), at(70, 50), at(420, 320), at(95, 15)};
  EXPECT_EQ(observeRegions(keys, boxes, moving), (std::vector<uint8_t>{1, 1, 0, 0}));
  // The chair becomes moving when most of its keypoints the geometric observation judged were seen moving
  // (a keypoint without a verdict, -1, does not count either way), and at least min_moved of them.
  const std::vector<cv::KeyPoint> chair_keys = {at(410, 310), at(420, 320), at(430, 330), at(440, 340),
                                                at(450, 350), at(460, 360), at(10, 200)};
  const int min_moved = 3;
  const auto share = movedShareInBoxes(chair_keys, boxes, {1, 1, 0, -1, 1, 0, 1}, min_moved);
  EXPECT_NEAR(share[3], 3.0 / 5.0, 1e-6);
  EXPECT_EQ(movingBoxes(boxes, RegionOptions{}, share)[3], 1);
  // Once it stands still, its keypoints are where they should be, and its box no longer counts.
  const auto still = movedShareInBoxes(chair_keys, boxes, {0, 0, 1, -1, 0, 0, 1}, min_moved);
  EXPECT_EQ(still[3], 0.0f);
  EXPECT_EQ(movingBoxes(boxes, RegionOptions{}, still)[3], 0);
  // The share decides once enough moved: with no minimum, 1 of its 5 judged is under the half.
  const auto few = movedShareInBoxes(chair_keys, boxes, {0, 0, 1, -1, 0, 0, 1}, 1);
  EXPECT_NEAR(few[3], 1.0 / 5.0, 1e-6);
  EXPECT_EQ(movingBoxes(boxes, RegionOptions{}, few)[3], 0);
  // A still chair with one keypoint judged, and that one a mismatch seen moving: one verdict is no evidence.
  const auto lone = movedShareInBoxes(chair_keys, boxes, {1, -1, -1, -1, -1, -1, 1}, min_moved);
  EXPECT_EQ(lone[3], 0.0f);
  EXPECT_EQ(movingBoxes(boxes, RegionOptions{}, lone)[3], 0);
  EXPECT_EQ(movingBoxes(boxes, RegionOptions{},
                        movedShareInBoxes(chair_keys, boxes, {1, -1, -1, -1, -1, -1, 1}, 1))[3],
            1)
      << "without the minimum the lone verdict counts";
}

// Real time: boxes 0.2 s old stand in for a frame's own; a person walking out of the old box is caught by the
// growth, the monitor behind them is not grown over them.
TEST(DynamicRegions, StaleBoxesGrowWithTheirAgeButLowBoxesStay) {
  const std::vector<ObjectBox> boxes = {box(100, 100, 80, 200, DynamicLevel::kHigh),
                                        box(300, 100, 60, 60, DynamicLevel::kMedium),
                                        box(200, 150, 50, 40, DynamicLevel::kLow)};
  const auto grown = grownForAge(boxes, 0.2, 250.0);  // 50 px on every side
  EXPECT_FLOAT_EQ(grown[0].box.x, 50.0f);
  EXPECT_FLOAT_EQ(grown[0].box.width, 180.0f);
  EXPECT_FLOAT_EQ(grown[0].box.height, 300.0f);
  EXPECT_FLOAT_EQ(grown[1].box.y, 50.0f);
  EXPECT_EQ(grown[2].box, boxes[2].box);
  // A keypoint 30 px right of the old person box: outside it, inside the grown one.
  const std::vector<cv::KeyPoint> keys = {at(210, 120)};
  EXPECT_EQ(observeRegions(keys, boxes, movingBoxes(boxes, RegionOptions{}))[0], 0);
  EXPECT_EQ(observeRegions(keys, grown, movingBoxes(grown, RegionOptions{}))[0], 1);
  EXPECT_EQ(grownForAge(boxes, -1.0, 250.0)[0].box, boxes[0].box) << "no shrinking";
}

// Real time: the newest boxes (0.1 s after the answer before) stand in for a frame 0.05 s after them. The
// person walked 20 px right in those 0.1 s, so their box goes on 10 px more; the chair of another class at
// the person's old place gives no speed, the box with no partner stays, and so does the monitor (low) that
// stood still in the image.
TEST(DynamicRegions, StaleBoxesMoveOnAtTheSpeedTheyShowed) {
  const std::vector<ObjectBox> before = {box(80, 100, 80, 200, DynamicLevel::kHigh),
                                         box(500, 300, 40, 40, DynamicLevel::kHigh),
                                         box(200, 150, 50, 40, DynamicLevel::kLow)};
  std::vector<ObjectBox> newest = {box(100, 104, 80, 200, DynamicLevel::kHigh),
                                   box(300, 100, 60, 60, DynamicLevel::kHigh),
                                   box(200, 150, 50, 40, DynamicLevel::kLow)};
  newest[1].class_id = 56;  // a chair: its own class, nothing of it before
  const auto moved = movedForAge(newest, before, 0.1, 0.05, 0.3);
  EXPECT_FLOAT_EQ(moved[0].box.x, 110.0f);
  EXPECT_FLOAT_EQ(moved[0].box.y, 106.0f);
  EXPECT_FLOAT_EQ(moved[0].box.width, 80.0f) << "moved, not grown";
  EXPECT_EQ(moved[1].box, newest[1].box);
  EXPECT_EQ(moved[2].box, newest[2].box);
  // The small box before overlaps nothing: a partner needs the overlap.
  const std::vector<ObjectBox> far = {box(400, 100, 80, 200, DynamicLevel::kHigh)};
  EXPECT_EQ(movedForAge(newest, far, 0.1, 0.05, 0.3)[0].box, newest[0].box);
  EXPECT_EQ(movedForAge(newest, before, 0.0, 0.05, 0.3)[0].box, newest[0].box) << "no speed from no time";
}

// The camera turns: everything, the monitor (low) with the person, moved 30 px left in the image in the
// 0.1 s between the answers. The stale low box moves on with the image, or its veto would fall on the
// person's pixels where the monitor was and leave the monitor's new place open.
TEST(DynamicRegions, AStaleLowBoxMovesWithTheImageWhenTheCameraTurns) {
  std::vector<ObjectBox> before = {box(330, 100, 80, 200, DynamicLevel::kHigh),
                                   box(230, 150, 100, 60, DynamicLevel::kLow)};
  std::vector<ObjectBox> newest = {box(300, 100, 80, 200, DynamicLevel::kHigh),
                                   box(200, 150, 100, 60, DynamicLevel::kLow)};
  before[1].class_id = newest[1].class_id = 62;  // a tv monitor
  const auto moved = movedForAge(newest, before, 0.1, 0.1, 0.3);
  EXPECT_FLOAT_EQ(moved[0].box.x, 270.0f);
  EXPECT_FLOAT_EQ(moved[1].box.x, 170.0f);
  EXPECT_FLOAT_EQ(moved[1].box.width, 100.0f) << "moved, not grown";
}

// The whole stand-in rule, as bmp-tracker and bmp-bench-tracker --box-lag apply it: the newest answer, moved
// on at the speed shown since the one before (when that one is recent), grown for its age; none when there
// is no answer or the newest is older than stale_box_max_age_s.
TEST(DynamicRegions, StandInBoxesFollowTheRealTimeRule) {
  DynamicOptions options;
  options.stale_box_max_age_s = 0.5;
  options.stale_box_motion_iou = 0.3;
  options.stale_box_growth_px_per_s = 100.0;
  const FrameBoxes older{1'000'000, true, {box(80, 100, 80, 200, DynamicLevel::kHigh)}};
  const FrameBoxes newest{1'100'000, true, {box(100, 100, 80, 200, DynamicLevel::kHigh)}};
  EXPECT_FALSE(standInBoxes({}, 1'150'000, options)) << "no answer yet: priors only";
  EXPECT_FALSE(standInBoxes({newest, older}, 1'700'000, options)) << "0.6 s old: too old";
  EXPECT_FALSE(standInBoxes({newest, older}, 1'100'000, options)) << "no age: not a stand-in";
  // 0.05 s after the newest: 10 px on at 200 px/s, and 5 px grown on every side.
  const auto moved = standInBoxes({newest, older}, 1'150'000, options);
  ASSERT_TRUE(moved);
  EXPECT_FLOAT_EQ((*moved)[0].box.x, 105.0f);
  EXPECT_FLOAT_EQ((*moved)[0].box.width, 90.0f);
  // Only one answer, or the one before too long before: grown where it was, not moved.
  EXPECT_FLOAT_EQ((*standInBoxes({newest}, 1'150'000, options))[0].box.x, 95.0f);
  const FrameBoxes long_before{500'000, true, older.boxes};
  EXPECT_FLOAT_EQ((*standInBoxes({newest, long_before}, 1'150'000, options))[0].box.x, 95.0f);
  options.stale_box_motion_iou = 0.0;
  EXPECT_FLOAT_EQ((*standInBoxes({newest, older}, 1'150'000, options))[0].box.x, 95.0f) << "motion off";
}

}  // namespace
}  // namespace bmp::tracker

// Persons the detector found in two answers in a row and misses in the next are held for a while.
#include <gtest/gtest.h>

#include "tracker/held_boxes.hpp"

namespace bmp::tracker {
namespace {

ObjectBox person(float x, float y = 100.0f) {
  ObjectBox b;
  b.box = cv::Rect2f(x, y, 80.0f, 200.0f);
  b.level = DynamicLevel::kHigh;
  b.class_id = 0;
  b.score = 0.5f;
  return b;
}

using Boxes = std::vector<ObjectBox>;
constexpr double kDt = 0.1;  // seconds between answers here

TEST(HeldBoxes, APersonMissedAfterTwoAnswersIsHeldAndMovedOnAtItsSpeed) {
  HeldBoxes held(0.5, 0.3);
  EXPECT_EQ(held.complete(Boxes{person(100)}, 0.0)->size(), 1u);
  EXPECT_EQ(held.complete(Boxes{person(110)}, kDt)->size(), 1u) << "found: nothing added";
  // Missed: held where 100 px/s takes it, with its class and level.
  const auto missed = held.complete(Boxes{}, 2 * kDt);
  ASSERT_TRUE(missed);
  ASSERT_EQ(missed->size(), 1u);
  EXPECT_FLOAT_EQ((*missed)[0].box.x, 120.0f);
  EXPECT_FLOAT_EQ((*missed)[0].box.y, 100.0f);
  EXPECT_EQ((*missed)[0].class_id, 0);
  EXPECT_EQ((*missed)[0].level, DynamicLevel::kHigh);
  EXPECT_FLOAT_EQ(held.complete(Boxes{}, 3 * kDt)->at(0).box.x, 130.0f);
  // Found again where it was expected: that box, not a second one beside it.
  const auto found = held.complete(Boxes{person(142)}, 4 * kDt);
  ASSERT_EQ(found->size(), 1u);
  EXPECT_FLOAT_EQ((*found)[0].box.x, 142.0f);
  // Its speed since it was last found (32 px in 0.3 s), held again on the next miss.
  EXPECT_NEAR(held.complete(Boxes{}, 5 * kDt)->at(0).box.x, 142.0f + 32.0f / 3.0f, 1e-3);
}

TEST(HeldBoxes, AHeldBoxLastsHoldSecondsFromWhenItWasLastFound) {
  HeldBoxes held(0.5, 0.3);
  held.complete(Boxes{person(100)}, 0.0);
  held.complete(Boxes{person(100)}, kDt);  // standing still: held where it is
  for (int i = 2; i <= 5; ++i) {           // up to 0.4 s after it was found
    const auto boxes = held.complete(Boxes{}, i * kDt);
    ASSERT_EQ(boxes->size(), 1u) << "frame " << i;
    EXPECT_FLOAT_EQ((*boxes)[0].box.x, 100.0f);
  }
  EXPECT_TRUE(held.complete(Boxes{}, 7 * kDt)->empty()) << "0.6 s after it was found: let go";
  EXPECT_TRUE(held.complete(Boxes{}, 8 * kDt)->empty());
}

TEST(HeldBoxes, OnlyPersonsFoundTwiceInARowAreHeld) {
  HeldBoxes held(0.5, 0.3);
  // Found once (a false detection, or a person just come): no speed, not held.
  held.complete(Boxes{person(100)}, 0.0);
  EXPECT_TRUE(held.complete(Boxes{}, kDt)->empty());
  // Two answers, but the box jumped (no overlap): a different object, not held.
  held.complete(Boxes{person(100)}, 2 * kDt);
  held.complete(Boxes{person(400)}, 3 * kDt);
  const auto jumped = held.complete(Boxes{}, 4 * kDt);
  EXPECT_TRUE(jumped->empty());
  // Low- and medium-dynamic boxes are the detector's alone.
  ObjectBox chair = person(100);
  chair.level = DynamicLevel::kMedium;
  chair.class_id = 56;
  held.complete(Boxes{chair}, 5 * kDt);
  held.complete(Boxes{chair}, 6 * kDt);
  EXPECT_TRUE(held.complete(Boxes{}, 7 * kDt)->empty());
  // Another class where the person was is not the person found again.
  held.complete(Boxes{person(100)}, 8 * kDt);
  held.complete(Boxes{person(100)}, 9 * kDt);
  ObjectBox dog = person(100);
  dog.class_id = 16;
  EXPECT_EQ(held.complete(Boxes{dog}, 10 * kDt)->size(), 2u) << "the dog, and the person held";
}

TEST(HeldBoxes, NoAnswerChangesNothingAndTimeGoingBackForgets) {
  HeldBoxes held(0.5, 0.3);
  held.complete(Boxes{person(100)}, 0.0);
  held.complete(Boxes{person(110)}, kDt);
  EXPECT_FALSE(held.complete(std::nullopt, 2 * kDt)) << "no answer stays no answer";
  EXPECT_FLOAT_EQ(held.complete(Boxes{}, 3 * kDt)->at(0).box.x, 130.0f);
  EXPECT_TRUE(held.complete(Boxes{}, 0.5 * kDt)->empty()) << "a stamp from the past starts again";
  HeldBoxes off(0.0, 0.3);
  off.complete(Boxes{person(100)}, 0.0);
  off.complete(Boxes{person(110)}, kDt);
  EXPECT_TRUE(off.complete(Boxes{}, 2 * kDt)->empty()) << "held_box_s 0: the detector's boxes only";
}

}  // namespace
}  // namespace bmp::tracker

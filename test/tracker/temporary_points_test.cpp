// Temporary points for the motion model: the last frame's nearest keypoints with depth, never a keypoint the
// dynamic stage saw as dynamic (they are near, and people are what is nearest in a crowd).
#include <gtest/gtest.h>

#include "room_rig.hpp"
#include "tracker/map_point.hpp"
#include "tracker/temporary_points.hpp"

namespace bmp::tracker {
namespace {

TEST(TemporaryPoints, NearestKeypointsWithDepthButNoDynamicOne) {
  const test_rig::RoomRig rig;
  const cv::Mat room = test_rig::loadRoom();
  ASSERT_FALSE(room.empty()) << "images missing under " << test::sharedDir();
  cv::Mat depth(480, 640, CV_32FC1, cv::Scalar(4.0f));
  const cv::Rect person(200, 100, 200, 300);
  depth(person).setTo(1.5f);  // the nearest keypoints are the person's
  Frame last = rig.frame(0, room, depth);
  const Features& f = *last.features;
  int on_person = 0;
  for (int i = 0; i < f.size(); ++i) {
    last.dynamic[i] = person.contains(f.keys[i].pt);
    on_person += last.dynamic[i];
  }
  ASSERT_GT(on_person, 50);
  const int made = addTemporaryPoints(last, rig.g, on_person);
  EXPECT_EQ(made, on_person) << "as many as asked, from the room behind";
  for (int i = 0; i < f.size(); ++i) {
    if (!last.points[i]) continue;
    EXPECT_FALSE(last.isDynamic(i)) << "keypoint " << i;
    EXPECT_TRUE(last.points[i]->temporary());
  }
  // Nothing seen as dynamic: the person's keypoints, the nearest, are taken first.
  Frame plain = rig.frame(0, room, depth);
  addTemporaryPoints(plain, rig.g, on_person);
  int taken_on_person = 0;
  for (int i = 0; i < f.size(); ++i) taken_on_person += plain.points[i] && person.contains(f.keys[i].pt);
  EXPECT_EQ(taken_on_person, on_person);
}

}  // namespace
}  // namespace bmp::tracker

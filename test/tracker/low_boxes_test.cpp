// A low-dynamic object (a TV, a laptop) inside a person's box: the paper keeps every keypoint in the low
// box out of the person's region. With the depth refinement the person's depth is known, so a keypoint at
// that depth is the person's even inside the TV's box (an arm in front of the screen), and the screen behind
// stays static. A real TUM frame gives the texture; the depth image is drawn.
#include <gtest/gtest.h>

#include "room_rig.hpp"
#include "tracker/dynamic_stage.hpp"

namespace bmp::tracker {
namespace {

constexpr float kRoomDepth = 4.0f, kPersonDepth = 1.5f, kScreenDepth = 3.5f;
const cv::Rect kPerson(150, 80, 300, 380);
const cv::Rect kScreen(200, 150, 120, 90);
const cv::Rect kArm(200, 150, 60, 90);  // the screen's left half: the person's arm in front of it

struct Counts {
  int arm = 0, arm_in = 0;        // keypoints on the arm, and of them observed as the mover's (z = d)
  int screen = 0, screen_in = 0;  // on the screen's uncovered half
  int body = 0, body_in = 0;      // on the person outside the screen's box
};

Counts observe(DynamicMode mode) {
  const test_rig::RoomRig rig;
  const cv::Mat room = test_rig::loadRoom();
  cv::Mat depth(480, 640, CV_32FC1, cv::Scalar(kRoomDepth));
  depth(kPerson).setTo(kPersonDepth);
  depth(kScreen).setTo(kScreenDepth);
  depth(kArm).setTo(kPersonDepth);
  Frame f = rig.frame(0, room, depth);
  DynamicOptions options;
  options.mode = mode;
  const DynamicStage stage(options, rig.config.pose);
  const std::vector<ObjectBox> boxes{{cv::Rect2f(kPerson), DynamicLevel::kHigh, 0, 0.9f},
                                     {cv::Rect2f(kScreen), DynamicLevel::kLow, 62, 0.8f}};
  stage.observe(f, &boxes, nullptr);
  Counts c;
  for (int k = 0; k < f.features->size(); ++k) {
    const cv::Point2f& p = f.features->keys[k].pt;
    const bool in = f.box_z[k] != 0;
    if (test_rig::insideBy(kArm, p, 4)) {
      ++c.arm;
      c.arm_in += in;
    } else if (test_rig::insideBy(
                   cv::Rect(kScreen.x + kArm.width, kScreen.y, kScreen.width - kArm.width, kScreen.height), p,
                   4)) {
      ++c.screen;
      c.screen_in += in;
    } else if (test_rig::insideBy(kPerson, p, 4) &&
               !cv::Rect(kScreen.x - 4, kScreen.y - 4, kScreen.width + 8, kScreen.height + 8).contains(p)) {
      ++c.body;
      c.body_in += in;
    }
  }
  return c;
}

TEST(LowBoxes, APersonInFrontOfAScreenIsTheMoverAtTheirDepth) {
  ASSERT_FALSE(test_rig::loadRoom().empty()) << "images missing under " << test::sharedDir();
  const Counts depth = observe(DynamicMode::kDepth);
  ASSERT_GT(depth.arm, 5);
  ASSERT_GT(depth.screen, 5);
  ASSERT_GT(depth.body, 50);
  EXPECT_EQ(depth.arm_in, depth.arm) << "the arm in front of the screen is the person's";
  EXPECT_EQ(depth.screen_in, 0) << "the screen behind the person stays static";
  EXPECT_EQ(depth.body_in, depth.body);
  // The paper's region test (no depth): the low box vetoes all of it, arm included.
  const Counts paper = observe(DynamicMode::kPaper);
  EXPECT_EQ(paper.arm_in, 0);
  EXPECT_EQ(paper.screen_in, 0);
  EXPECT_EQ(paper.body_in, paper.body);
}

}  // namespace
}  // namespace bmp::tracker

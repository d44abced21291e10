// A keyframe's own answer that comes late (real time) and holds a chair: the keyframe's own geometric
// verdicts are the evidence that the chair moves, as the next frame would have taken them. Without them the
// late answer counted a pushed chair as standing still and undid what the stand-in boxes had observed.
#include <gtest/gtest.h>

#include "room_rig.hpp"
#include "tracker/dynamic_stage.hpp"
#include "tracker/key_frame.hpp"

namespace bmp::tracker {
namespace {

const cv::Rect kChair(380, 260, 160, 160);

// The moving probabilities of the keypoints on the chair after the late answer, its frame's verdicts saying
// the chair's keypoints moved (or stayed).
std::vector<float> chairAfterLateAnswer(bool chair_moved) {
  const test_rig::RoomRig rig;
  const cv::Mat depth(480, 640, CV_32FC1, cv::Scalar(3.0f));
  Frame f = rig.frame(0, test_rig::loadRoom(), depth);
  DynamicOptions options;
  options.mode = DynamicMode::kGeometric;
  const DynamicStage stage(options, rig.config.pose);
  stage.applyPriors(f);  // nothing matched, no boxes yet: the unmatched prior
  f.moved.assign(f.features->keys.size(), 0);
  for (int k = 0; k < f.features->size(); ++k)
    if (test_rig::insideBy(kChair, f.features->keys[k].pt, 4)) f.moved[k] = chair_moved ? 1 : 0;
  KeyFrame kf(0, f);
  const std::vector<ObjectBox> late{{cv::Rect2f(kChair), DynamicLevel::kMedium, 56, 0.8f}};
  stage.observeLate(kf, late);
  std::vector<float> chair;
  for (int k = 0; k < f.features->size(); ++k)
    if (test_rig::insideBy(kChair, f.features->keys[k].pt, 4)) chair.push_back(kf.moving[k]);
  return chair;
}

TEST(LateAnswers, AChairTheKeyframeSawMovingCountsAsMoving) {
  ASSERT_FALSE(test_rig::loadRoom().empty()) << "images missing under " << test::sharedDir();
  const std::vector<float> pushed = chairAfterLateAnswer(true);
  ASSERT_GT(pushed.size(), 10u);
  for (const float p : pushed) EXPECT_NEAR(p, 0.9, 1e-6) << "z = d on the unmatched prior";
  const std::vector<float> still = chairAfterLateAnswer(false);
  for (const float p : still) EXPECT_NEAR(p, 0.1, 1e-6) << "a chair not seen moving is static";
}

}  // namespace
}  // namespace bmp::tracker

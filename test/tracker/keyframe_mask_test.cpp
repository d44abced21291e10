// The keyframe's dynamic mask, which the mapper leaves out of the map. A mover no detector knows has only
// some of its keypoints judged dynamic at any time; with the geometric observation their cluster marks the
// whole of the mover at its depth, not a disk around each of them, so the rest of it does not become a
// ghost in the map. A person's box region is not widened by a cluster. A real TUM frame gives the texture;
// the depth image is drawn.
#include <gtest/gtest.h>

#include "room_rig.hpp"
#include "tracker/dynamic_stage.hpp"

namespace bmp::tracker {
namespace {

constexpr float kRoomDepth = 4.0f, kMoverDepth = 2.0f;
const cv::Rect kMover(200, 120, 200, 240);  // a box the detector does not know, in front of the room

struct Masked {
  double mover = 0, room = 0;  // shares of the mover's and of the room's pixels in the mask
};

Masked maskShares(const cv::Mat& m) {
  cv::Mat mover = cv::Mat::zeros(m.size(), CV_8UC1);
  mover(kMover).setTo(255);
  const double on_mover = cv::countNonZero(m & mover);
  return {on_mover / kMover.area(), (cv::countNonZero(m) - on_mover) / (m.total() - kMover.area())};
}

class KeyframeMask : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_FALSE(test_rig::loadRoom().empty()) << "images missing under " << test::sharedDir();
    depth_ = cv::Mat(480, 640, CV_32FC1, cv::Scalar(kRoomDepth));
    depth_(kMover).setTo(kMoverDepth);
    frame_ = std::make_unique<Frame>(rig_.frame(0, test_rig::loadRoom(), depth_));
    // Every third keypoint on the mover judged dynamic: most of a mover's keypoints are new in a frame.
    const Features& f = *frame_->features;
    dynamic_.assign(f.keys.size(), 0);
    int on_mover = 0;
    for (int k = 0; k < f.size(); ++k)
      if (kMover.contains(f.keys[k].pt) && on_mover++ % 3 == 0) dynamic_[k] = 1;
    ASSERT_GT(on_mover, 30);
  }
  cv::Mat mask(DynamicMode mode, const std::vector<ObjectBox>* boxes,
               const std::vector<float>& moving_share = {}) const {
    DynamicOptions o;
    o.mode = mode;
    return DynamicStage(o, rig_.config.pose)
        .mask(*frame_->features, rig_.g, dynamic_, boxes, moving_share, depth_, 1.0);
  }

  test_rig::RoomRig rig_;
  cv::Mat depth_;
  std::unique_ptr<Frame> frame_;
  std::vector<uint8_t> dynamic_;
};

TEST_F(KeyframeMask, AClusterOfDynamicKeypointsMasksTheWholeMoverAtItsDepth) {
  const Masked geometric = maskShares(mask(DynamicMode::kGeometric, nullptr));
  EXPECT_GT(geometric.mover, 0.85) << "the mover's pixels between its judged keypoints";
  EXPECT_LT(geometric.room, 0.01) << "the room behind, inside the cluster's box but at another depth";
  // Without the geometric observation: disks around the judged keypoints only.
  const Masked depth = maskShares(mask(DynamicMode::kDepth, nullptr));
  EXPECT_LT(depth.mover, 0.6);
  EXPECT_LT(depth.room, 0.01);
}

TEST_F(KeyframeMask, APersonsRegionIsNotWidenedByItsCluster) {
  // The mover is a person the detector boxed; a cupboard stands just beside them, a little further back.
  // The region is the box cut by depth, and the keypoints in it make no cluster region of their own: its
  // box, grown, would take the cupboard (and, over several people, the floor between them).
  const cv::Rect cupboard(kMover.br().x, kMover.y, 40, kMover.height);
  depth_(cupboard).setTo(kMoverDepth + 0.2f);
  const std::vector<ObjectBox> boxes{{cv::Rect2f(kMover), DynamicLevel::kHigh, 0, 0.9f}};
  const cv::Mat with = mask(DynamicMode::kGeometric, &boxes);
  EXPECT_EQ(cv::countNonZero(with != mask(DynamicMode::kDepth, &boxes)), 0);
  EXPECT_GT(maskShares(with).mover, 0.99);
  // Beyond the disks around the keypoints judged dynamic near its edge, the cupboard stays in the map.
  EXPECT_EQ(cv::countNonZero(with(cv::Rect(cupboard.x + 13, cupboard.y, 27, cupboard.height))), 0);
}

// The mover is a chair someone pushes: its keypoints were seen moving, so the frame kept them out, and the
// mask must cover it as well (given no evidence, the mask left the whole box out, and the mapper put the
// chair where it passed). Standing still, it is not masked beyond its judged keypoints' disks.
TEST_F(KeyframeMask, AChairSeenMovingIsMaskedAsItWasKeptOut) {
  const std::vector<ObjectBox> chair{{cv::Rect2f(kMover), DynamicLevel::kMedium, 56, 0.8f}};
  EXPECT_GT(maskShares(mask(DynamicMode::kDepth, &chair, {1.0f})).mover, 0.95);
  EXPECT_LT(maskShares(mask(DynamicMode::kDepth, &chair, {0.0f})).mover, 0.6);
  EXPECT_LT(maskShares(mask(DynamicMode::kDepth, &chair, {1.0f})).room, 0.01);
}

}  // namespace
}  // namespace bmp::tracker

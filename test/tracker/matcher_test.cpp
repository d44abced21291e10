// Projection search with a depth camera: a keypoint takes a map point only where its measured depth agrees
// with the point's. A real TUM frame is the room, 4 m away; in the next frame the same pixels stand 2.2 m
// away inside a rectangle (an occluder carrying the wall's texture, so that every descriptor agrees and only
// depth can tell). The right-image gate alone, scaled by the pyramid level, lets coarse keypoints through:
// in a real run a person's keypoint took the wall point behind it, and with it the wall's static history.
#include <gtest/gtest.h>

#include <memory>

#include "room_rig.hpp"
#include "tracker/key_frame.hpp"
#include "tracker/map.hpp"
#include "tracker/map_point.hpp"
#include "tracker/matcher.hpp"

namespace bmp::tracker {
namespace {

constexpr double kRoomDepth = 4.0, kOccluderDepth = 2.2;
const cv::Rect kOccluder(200, 120, 240, 240);

struct Rig : test_rig::RoomRig {
  cv::Mat room = test_rig::loadRoom();
  Frame frame(int seq, bool occluded) const {
    cv::Mat depth(480, 640, CV_32FC1, cv::Scalar(kRoomDepth));
    if (occluded) depth(kOccluder).setTo(kOccluderDepth);
    return RoomRig::frame(seq, room, depth);
  }
};

// The last frame with a map point on each of its keypoints (the camera at the origin).
Frame withPoints(const Rig& rig, Frame last) {
  const Features& f = *last.features;
  for (int i = 0; i < f.size(); ++i) {
    if (!f.hasDepth(i)) continue;
    auto mp = std::make_shared<MapPoint>(i, rig.g.camera.backProject(f.un[i], f.depth[i]),
                                         f.descriptors.row(i).clone(), 0);
    mp->initGeometry(Eigen::Vector3d::Zero(), f.level(i), rig.g);
    last.points[i] = mp;
  }
  return last;
}

struct Matched {
  int inside = 0, outside = 0;  // keypoints of the current frame matched, in the occluder and around it
};

Matched match(const Rig& rig, const Frame& last, double depth_ratio) {
  Frame now = rig.frame(1, true);
  TrackingOptions o = rig.config.tracking;
  o.match_depth_ratio = depth_ratio;
  matchFromLastFrame(now, last, rig.g, o, o.motion_search_radius);
  Matched m;
  const cv::Rect shrunk(kOccluder.x + 2, kOccluder.y + 2, kOccluder.width - 4, kOccluder.height - 4);
  const cv::Rect grown(kOccluder.x - 2, kOccluder.y - 2, kOccluder.width + 4, kOccluder.height + 4);
  for (int i = 0; i < now.features->size(); ++i) {
    if (!now.points[i]) continue;
    // The rim's keypoints read depth on either side of the edge: counted as neither.
    const cv::Point2f& p = now.features->keys[i].pt;
    if (shrunk.contains(p))
      ++m.inside;
    else if (!grown.contains(p))
      ++m.outside;
  }
  return m;
}

TEST(ProjectionMatching, AKeypointInFrontOfAMapPointIsNotThatPoint) {
  const Rig rig;
  ASSERT_FALSE(rig.room.empty()) << "images missing under " << test::sharedDir();
  const Frame last = withPoints(rig, rig.frame(0, false));
  const Matched gated = match(rig, last, TrackingOptions{}.match_depth_ratio);
  const Matched ungated = match(rig, last, 0.0);
  EXPECT_GT(ungated.inside, 20) << "without the depth gate the occluder's keypoints take the wall's points";
  EXPECT_EQ(gated.inside, 0);
  EXPECT_GT(gated.outside, 100);
  // Where depth agrees the gate changes nothing but the greedy order (a point near the rim may take a
  // neighbour's keypoint once its own is refused): within 1 %.
  EXPECT_NEAR(gated.outside, ungated.outside, 0.01 * ungated.outside);
}

// Depth within the gate (5 % off at the default 8 %: 20 cm at 4 m, where a Kinect's depth noise is 2-4 cm),
// as noise and a predicted pose's error give it.
TEST(ProjectionMatching, DepthAsNoisyAsASensorsStillMatches) {
  const Rig rig;
  ASSERT_FALSE(rig.room.empty()) << "images missing under " << test::sharedDir();
  Frame last = withPoints(rig, rig.frame(0, false));
  for (auto& mp : last.points)
    if (mp) mp->p_world *= 1.05;  // every point 5 % further along its ray: the same pixel
  Frame now = rig.frame(1, false);
  const TrackingOptions o = rig.config.tracking;
  const int n = matchFromLastFrame(now, last, rig.g, o, o.motion_search_radius);
  int expected = 0;
  for (const auto& mp : last.points) expected += mp != nullptr;
  EXPECT_GT(n, 0.9 * expected);
}

// Fusion projects the neighbours' points into a new keyframe. A keypoint the keyframe saw as dynamic (a
// person's) must not take one: its observation would pull the static point, and the keyframe, in local BA.
// The points here are the frame's own, so every keypoint with depth finds its point again.
TEST(Fusion, AKeypointSeenAsDynamicTakesNoPoint) {
  const Rig rig;
  ASSERT_FALSE(rig.room.empty()) << "images missing under " << test::sharedDir();
  const Frame source = withPoints(rig, rig.frame(0, false));
  Frame frame = rig.frame(0, false);
  const Features& f = *frame.features;
  for (int i = 0; i < f.size(); ++i) frame.dynamic[i] = f.keys[i].pt.x < 320;  // a person on the left half
  Map map;
  auto kf = std::make_shared<KeyFrame>(map.newKeyFrameId(), frame);
  map.addKeyFrame(kf);
  std::vector<std::shared_ptr<MapPoint>> points;
  for (const auto& mp : source.points)
    if (mp) {
      map.addPoint(mp);
      points.push_back(mp);
    }
  const MatcherOptions m = rig.config.matcher;
  const int fused = fusePoints(map, kf.get(), points, rig.g, m, 3.0, 7.81);
  int on_dynamic = 0, on_static = 0, static_with_depth = 0;
  for (int i = 0; i < f.size(); ++i) {
    if (kf->dynamic[i]) {
      on_dynamic += kf->points[i] != nullptr;
    } else {
      on_static += kf->points[i] != nullptr;
      static_with_depth += f.hasDepth(i);
    }
  }
  EXPECT_EQ(on_dynamic, 0);
  EXPECT_GT(on_static, 0.9 * static_with_depth) << "the static half takes its points";
  EXPECT_EQ(fused, on_static);
}

}  // namespace
}  // namespace bmp::tracker

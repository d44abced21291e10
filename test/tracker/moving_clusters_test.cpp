// Moving clusters: keypoints that moved, linked in the image and in depth, are a mover when they outnumber
// the keypoints that stayed in their region.
#include <gtest/gtest.h>

#include <algorithm>

#include "tracker/moving_clusters.hpp"

namespace bmp::tracker {
namespace {

struct Scene {
  CameraIntrinsics k;  // 525, 319.5, 239.5, no distortion
  TrackerConfig config;
  FrameGeometry g{k, config};
  OrbFeatures orb;
  std::vector<float> depths;
  std::vector<int8_t> verdict;
  int add(float x, float y, float depth, int8_t v) {
    cv::KeyPoint kp(x, y, 31.0f);
    kp.octave = 0;
    orb.keys.push_back(kp);
    depths.push_back(depth);
    verdict.push_back(v);
    return static_cast<int>(orb.keys.size()) - 1;
  }
  std::shared_ptr<const Features> features() {
    orb.descriptors = cv::Mat::zeros(static_cast<int>(orb.keys.size()), kDescriptorBytes, CV_8U);
    // Each keypoint's depth painted under it (3x3), the rest of the image without depth.
    cv::Mat depth = cv::Mat::zeros(480, 640, CV_32FC1);
    for (std::size_t i = 0; i < orb.keys.size(); ++i)
      depth(cv::Rect(cvRound(orb.keys[i].pt.x) - 1, cvRound(orb.keys[i].pt.y) - 1, 3, 3)).setTo(depths[i]);
    return buildFeatures(orb, depth, g, nullptr, cv::Mat());
  }
};

TEST(MovingClusters, AMoverIsAClusterItsStaticSurroundIsNot) {
  Scene s;
  // A body 2 m away: 9 keypoints that moved on a 3x3 lattice 25 px apart, one that stayed (a fresh track),
  // and two with no verdict inside it.
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) s.add(100.0f + 25 * c, 100.0f + 25 * r, 2.0f, 1);
  s.add(112.0f, 112.0f, 2.05f, 0);
  const int inside = s.add(140.0f, 140.0f, 2.1f, -1);
  const int behind = s.add(130.0f, 130.0f, 3.5f, -1);  // in the box, but a wall behind the body
  // A wall 4 m away: 6 mismatches that "moved", strung 50 px apart, among 20 keypoints that stayed.
  for (int c = 0; c < 6; ++c) s.add(300.0f + 50 * c, 290.0f + 20 * (c % 2), 4.0f, 1);
  for (int c = 0; c < 20; ++c) s.add(303.0f + 12 * c, 300.0f, 4.0f, 0);
  // Two keypoints that moved 3 m away: too few to be a body.
  s.add(500.0f, 100.0f, 3.0f, 1), s.add(520.0f, 100.0f, 3.0f, 1);
  const auto f = s.features();
  ASSERT_EQ(f->size(), static_cast<int>(s.verdict.size()));

  const auto clusters = movingClusters(*f, s.g, s.verdict, 60.0, 0.3, 5);
  ASSERT_EQ(clusters.size(), 1u);
  const MovingCluster& body = clusters.front();
  EXPECT_EQ(body.size, 9);
  EXPECT_NEAR(body.near_m, 2.0, 1e-3);
  EXPECT_NEAR(body.far_m, 2.0, 1e-3);
  EXPECT_TRUE(body.covers(f->un[inside].x(), f->un[inside].y(), f->depth[inside], 0.3));
  EXPECT_FALSE(body.covers(f->un[behind].x(), f->un[behind].y(), f->depth[behind], 0.3));

  // With fewer keypoints that stayed on the wall than moved, the wall would be taken for a mover: the
  // majority rule is what keeps it.
  std::vector<int8_t> fewer = s.verdict;
  for (std::size_t i = 0; i < fewer.size(); ++i)
    if (f->depth[i] > 3.9f && fewer[i] == 0 && i % 4 != 0) fewer[i] = -1;
  EXPECT_EQ(movingClusters(*f, s.g, fewer, 60.0, 0.3, 5).size(), 2u);
  // Depth splits what the image joins: the body at 2 m and a second group 1 m behind it are two clusters.
  EXPECT_EQ(movingClusters(*f, s.g, s.verdict, 60.0, 0.3, 2).size(), 2u);

  // A keypoint outside the frame's grid (beyond the bounds its corners give, under strong distortion) that
  // moved still links to the body's keypoints around it. Keypoint 0 is the body's first: only its own search
  // can link it, as no search finds a keypoint outside the grid.
  Features outside = *f;
  for (auto& cell : outside.grid) cell.erase(std::remove(cell.begin(), cell.end(), 0), cell.end());
  const auto joined = movingClusters(outside, s.g, s.verdict, 60.0, 0.3, 5);
  ASSERT_EQ(joined.size(), 1u);
  EXPECT_EQ(joined.front().size, 9);
  // No link distance: nothing links, so no body is big enough.
  EXPECT_TRUE(movingClusters(*f, s.g, s.verdict, 0.0, 0.3, 5).empty());
}

}  // namespace
}  // namespace bmp::tracker

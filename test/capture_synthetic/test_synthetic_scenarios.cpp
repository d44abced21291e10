// The synthetic scenarios: determinism, per-mover labels, exact depth on the people's silhouettes, the
// photos' backgrounds left out, and each scenario's timeline.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <memory>

#include "bmp/common/camera_model.hpp"
#include "bmp/common/timing.hpp"
#include "scenario_test_util.hpp"

namespace bmp::capture {
namespace {

using test::MoverView;
using test::scenarioConfig;

bool identical(const cv::Mat& a, const cv::Mat& b) {
  return a.size() == b.size() && a.type() == b.type() && cv::norm(a, b, cv::NORM_INF) == 0;
}

// One scene per scenario, built on first use and shared by the suite (scenes take a second to build).
class SyntheticScenarios : public ::testing::Test {
 protected:
  static void TearDownTestSuite() { scenes_.clear(); }
  static const SyntheticScene& scene(const std::string& name) {
    auto& s = scenes_[name];
    if (!s) s = std::make_unique<SyntheticScene>(scenarioConfig(name));
    return *s;
  }

 private:
  static std::map<std::string, std::unique_ptr<SyntheticScene>> scenes_;
};
std::map<std::string, std::unique_ptr<SyntheticScene>> SyntheticScenarios::scenes_;

TEST_F(SyntheticScenarios, ShippedFilesSelectTheirScenario) {
  for (const std::string& name : scenarioNames()) {
    const SyntheticSceneConfig c = scenarioConfig(name);
    EXPECT_EQ(toString(c.scenario), name);
    EXPECT_EQ(c.num_frames, 300);
    EXPECT_EQ(c.camera.width, 640);
    EXPECT_EQ(c.people.size(), 3u);
  }
  EXPECT_THROW(parseScenario("parade"), std::invalid_argument);
}

TEST_F(SyntheticScenarios, EveryScenarioRendersDeterministically) {
  for (const std::string& name : scenarioNames()) {
    SyntheticSceneConfig c = scenarioConfig(name);
    const SyntheticScene again(c);
    for (int index : {40, 170}) {
      const SyntheticFrame a = scene(name).render(index), b = again.render(index);
      EXPECT_TRUE(identical(a.bgr, b.bgr) && identical(a.depth, b.depth) && identical(a.mask, b.mask) &&
                  identical(a.mover_ids, b.mover_ids))
          << name << " frame " << index;
      ASSERT_EQ(a.movers.size(), b.movers.size());
      // The mask is exactly the movers' pixels.
      EXPECT_TRUE(identical(a.mask, cv::Mat((a.mover_ids > 0))));
    }
    c.seed = 5;
    EXPECT_FALSE(identical(SyntheticScene(c).render(40).bgr, scene(name).render(40).bgr)) << name;
  }
}

TEST_F(SyntheticScenarios, MoversAreLabelledByIdAndKind) {
  const std::map<std::string, std::pair<int, int>> expected{// boxes, people
                                                            {"boxes", {2, 0}},
                                                            {"people_walking", {0, 3}},
                                                            {"person_stops", {0, 1}},
                                                            {"crowd", {0, 10}},
                                                            {"unknown_mover", {1, 1}}};
  for (const auto& [name, counts] : expected) {
    const SyntheticFrame f = scene(name).render(100);
    int boxes = 0, people = 0;
    for (std::size_t i = 0; i < f.movers.size(); ++i) {
      EXPECT_EQ(f.movers[i].id, static_cast<int>(i) + 1);
      (f.movers[i].kind == MoverKind::kBox ? boxes : people)++;
    }
    EXPECT_EQ(boxes, counts.first) << name;
    EXPECT_EQ(people, counts.second) << name;
    double max_id = 0;
    cv::minMaxLoc(f.mover_ids, nullptr, &max_id);
    EXPECT_LE(max_id, static_cast<double>(f.movers.size())) << name;
  }
}

// Every mover pixel back-projects onto that mover's billboard (or box), and its silhouette edges are
// depth edges: the depth is the mover's own, exactly.
TEST_F(SyntheticScenarios, MoverPixelsHaveTheMoversDepth) {
  for (const std::string name : {"people_walking", "crowd", "unknown_mover"}) {
    const SyntheticScene& s = scene(name);
    const CameraModel model(s.camera());
    for (int index : {60, 150, 240}) {
      const SyntheticFrame f = s.render(index);
      const auto objects = s.movingObjects(index);
      int checked = 0;
      for (int v = 0; v < f.depth.rows; v += 3) {
        for (int u = 0; u < f.depth.cols; u += 3) {
          const int id = f.mover_ids.at<uint8_t>(v, u);
          if (id == 0) continue;
          const auto& o = objects[static_cast<std::size_t>(id - 1)];
          const Eigen::Vector3d p = o.T_world_object.inverse() *
                                    (f.T_world_cam * model.backProject({u, v}, f.depth.at<uint16_t>(v, u) /
                                                                                   s.camera().depth_scale));
          const double tol = 1e-3;
          const bool inside = ((p - o.box.lo).array() > -tol).all() && ((o.box.hi - p).array() > -tol).all();
          ASSERT_TRUE(inside) << name << " frame " << index << " pixel " << u << "," << v;
          ++checked;
        }
      }
      EXPECT_GT(checked, 200) << name << " frame " << index;
    }
  }
}

// Inside a person's billboard rectangle, the pixels off the silhouette show what lies behind or beside the
// billboard, never the billboard itself: the photo's background is not drawn.
TEST_F(SyntheticScenarios, PhotoBackgroundIsNotDrawn) {
  const SyntheticScene& s = scene("person_stops");
  const CameraIntrinsics& k = s.camera();
  for (int index : {90, 120, 150}) {  // the person stands in the middle of the view
    const SyntheticFrame f = s.render(index);
    const MovingObjectState person = s.movingObjects(index)[0];
    const auto views = test::moverViews(s, f);
    ASSERT_TRUE(views[0].in_front);
    ASSERT_GT(views[0].pixels, 10000);
    // The billboard's plane in the camera frame: depth z along the ray (xn, yn, 1) is (n . c) / (n . ray).
    const SE3 T_cam_object = f.T_world_cam.inverse() * person.T_world_object;
    const Eigen::Vector3d n = T_cam_object.linear().col(0), c = T_cam_object.translation();
    const cv::Rect r = cv::Rect(views[0].projected) & cv::Rect(0, 0, f.bgr.cols, f.bgr.rows);
    int off = 0, on_plane = 0;
    for (int v = r.y; v < r.y + r.height; ++v) {
      for (int u = r.x; u < r.x + r.width; ++u) {
        if (f.mover_ids.at<uint8_t>(v, u) != 0) continue;
        ++off;
        const Eigen::Vector3d ray((u - k.cx) / k.fx, (v - k.cy) / k.fy, 1.0);
        const double plane_z = n.dot(c) / n.dot(ray);
        if (std::abs(f.depth.at<uint16_t>(v, u) / k.depth_scale - plane_z) < 0.005) ++on_plane;
      }
    }
    std::printf("frame %d: %d of %d pixels of the person's rectangle off the silhouette, %d at its depth\n",
                index, off, r.area(), on_plane);
    EXPECT_GT(off, r.area() / 5);
    EXPECT_LT(on_plane, 0.01 * off);  // only where the floor meets the feet
  }
}

TEST_F(SyntheticScenarios, PersonStopsStandsThreeSeconds) {
  const SyntheticScene& s = scene("person_stops");
  int standing = 0, first = -1, last = -1;
  for (int i = 0; i < s.numFrames(); ++i) {
    const auto objects = s.movingObjects(i);
    ASSERT_EQ(objects.size(), 1u);
    if (objects[0].info.moving) continue;
    ++standing;
    if (first < 0) first = i;
    last = i;
  }
  EXPECT_NEAR(standing, 90, 2);
  EXPECT_EQ(last - first + 1, standing);  // one stop
  EXPECT_LT((s.movingObjects(first)[0].position - s.movingObjects(last)[0].position).norm(), 1e-9);
  EXPECT_TRUE(s.movingObjects(first - 5)[0].info.moving);
  EXPECT_TRUE(s.movingObjects(last + 5)[0].info.moving);
}

TEST_F(SyntheticScenarios, CrowdCoversOverHalfTheViewForTwoSeconds) {
  const SyntheticScene& s = scene("crowd");
  int covered = 0, longest = 0, run = 0;
  for (int i = 0; i < s.numFrames(); i += 3) {
    const SyntheticFrame f = s.render(i);
    const double share = cv::countNonZero(f.mask) / static_cast<double>(f.mask.total());
    run = share > 0.5 ? run + 3 : 0;
    covered += share > 0.5 ? 3 : 0;
    longest = std::max(longest, run);
  }
  std::printf("crowd: over half the view covered in %d frames, %d in a row\n", covered, longest);
  EXPECT_GE(longest, 60);
  EXPECT_EQ(cv::countNonZero(s.render(0).mask), 0);  // they come in from outside the room
}

}  // namespace
}  // namespace bmp::capture

// The real detector on the rendered scenarios: YOLOv5n finds the people cut out of photos, and no person
// on the textured box, so the synthetic scene exercises the tracker's detector path.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <memory>

#include "detector/detector.hpp"
#include "scenario_test_util.hpp"

namespace bmp::capture {
namespace {

struct Rates {
  int visible = 0;   // fully visible, unoccluded person movers taller than 100 pixels
  int detected = 0;  // of them, overlapped by a person box at IoU >= 0.5
  int box_visible = 0;
  int box_hits = 0;  // person boxes on the unknown box
};

std::vector<cv::Rect2d> personBoxes(detector::Detector& d, const cv::Mat& bgr) {
  std::vector<cv::Rect2d> out;
  for (const auto& det : d.detect(bgr))
    if (det.label == "person") out.emplace_back(det.box.x, det.box.y, det.box.width, det.box.height);
  return out;
}

void score(detector::Detector& d, const SyntheticScene& scene, int step, Rates& r) {
  for (int i = 0; i < scene.numFrames(); i += step) {
    const SyntheticFrame f = scene.render(i);
    const auto views = test::moverViews(scene, f);
    const auto people = personBoxes(d, f.bgr);
    for (std::size_t k = 0; k < views.size(); ++k) {
      const auto& v = views[k];
      double best = 0.0;
      for (const auto& p : people) best = std::max(best, test::iou(p, v.pixels_box));
      if (v.info.kind == MoverKind::kBox) {
        if (v.pixels < 2000) continue;
        ++r.box_visible;
        if (best >= 0.5) ++r.box_hits;
        continue;
      }
      if (!test::fullyVisible(views, k, f.bgr.size()) || v.pixels_box.height <= 100) continue;
      ++r.visible;
      if (best >= 0.5) ++r.detected;
    }
  }
}

class SyntheticYolo : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
    ASSERT_TRUE(std::filesystem::exists(test::sharedPath("images/bus.jpg")))
        << "no shared images in " << test::sharedDir() << " (set BMP_SHARED)";
    detector_ = std::make_unique<detector::Detector>(
        detector::withModelPreset(detector::DetectorConfig{}, GetParam()),
        Config::fromFile(test::sourceDir() + "/config/dynamic_classes.yaml"));
  }
  std::unique_ptr<detector::Detector> detector_;
};

TEST_P(SyntheticYolo, FindsTheRenderedPeople) {
  for (const auto& [name, step] : {std::pair<std::string, int>{"people_walking", 25}, {"person_stops", 12}}) {
    const SyntheticScene scene(test::scenarioConfig(name));
    Rates r;
    score(*detector_, scene, step, r);
    const double rate = r.detected / static_cast<double>(std::max(1, r.visible));
    std::printf("%s, %s: person found in %d of %d fully visible person views (%.0f %%)\n", GetParam().c_str(),
                name.c_str(), r.detected, r.visible, 100 * rate);
    EXPECT_GE(r.visible, 5) << name;
    EXPECT_GE(rate, 0.8) << name;
  }
}

TEST_P(SyntheticYolo, SeesNoPersonOnTheUnknownBox) {
  const SyntheticScene scene(test::scenarioConfig("unknown_mover"));
  Rates r;
  score(*detector_, scene, 25, r);
  std::printf("%s, unknown_mover: %d person boxes on the box in %d views; person found in %d of %d\n",
              GetParam().c_str(), r.box_hits, r.box_visible, r.detected, r.visible);
  EXPECT_GE(r.box_visible, 5);
  EXPECT_EQ(r.box_hits, 0);
  EXPECT_GE(r.detected, 0.8 * r.visible);
}

INSTANTIATE_TEST_SUITE_P(Models, SyntheticYolo, ::testing::Values("yolov5n-320", "yolov5n-640"),
                         [](const auto& info) { return info.param == "yolov5n-320" ? "v5n320" : "v5n640"; });

}  // namespace
}  // namespace bmp::capture

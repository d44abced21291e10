#pragma once
// Helpers shared by the scenario tests: scenario configurations and where each mover is in a frame.
#include <algorithm>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "bmp/common/config.hpp"
#include "capture/synthetic_config.hpp"
#include "capture/synthetic_scene.hpp"
#include "shared_data.hpp"

namespace bmp::test {

// The shipped scenario file config/synthetic/<name>.yaml ("boxes": config/synthetic.yaml).
inline capture::SyntheticSceneConfig scenarioConfig(const std::string& name) {
  const std::string file = name == "boxes" ? sourceDir() + "/config/synthetic.yaml"
                                           : sourceDir() + "/config/synthetic/" + name + ".yaml";
  const Config config = Config::fromFile(file);
  capture::SyntheticSceneConfig c = capture::syntheticSceneFromConfig(config.section("synthetic"));
  config.finish();
  return c;
}

// A mover in one frame: its pixels' bounding box, their count, its billboard's projected rectangle and
// its distance from the camera.
struct MoverView {
  capture::MoverInfo info;
  cv::Rect pixels_box;
  int pixels = 0;
  cv::Rect2d projected;  // the whole box or billboard, unclipped
  double distance = 0.0;
  bool in_front = false;  // every corner ahead of the camera
};

inline std::vector<MoverView> moverViews(const capture::SyntheticScene& scene,
                                         const capture::SyntheticFrame& f) {
  std::vector<MoverView> out;
  const auto objects = scene.movingObjects(f.index);
  const CameraIntrinsics& k = scene.camera();
  for (const auto& o : objects) {
    MoverView v;
    v.info = o.info;
    const cv::Mat mine = f.mover_ids == o.info.id;
    v.pixels = cv::countNonZero(mine);
    if (v.pixels > 0) v.pixels_box = cv::boundingRect(mine);
    double u0 = 1e9, u1 = -1e9, v0 = 1e9, v1 = -1e9;
    v.in_front = true;
    for (int i = 0; i < 8; ++i) {
      const Eigen::Vector3d q((i & 1) ? o.box.hi.x() : o.box.lo.x(), (i & 2) ? o.box.hi.y() : o.box.lo.y(),
                              (i & 4) ? o.box.hi.z() : o.box.lo.z());
      const Eigen::Vector3d p = f.T_world_cam.inverse() * (o.T_world_object * q);
      if (p.z() < 0.1) {
        v.in_front = false;
        continue;
      }
      const double u = k.fx * p.x() / p.z() + k.cx, w = k.fy * p.y() / p.z() + k.cy;
      u0 = std::min(u0, u), u1 = std::max(u1, u), v0 = std::min(v0, w), v1 = std::max(v1, w);
    }
    v.projected = cv::Rect2d(u0, v0, u1 - u0, v1 - v0);
    v.distance = (f.T_world_cam.inverse() * o.T_world_object.translation()).z();
    out.push_back(v);
  }
  return out;
}

// Whole in the image and not behind another mover's rectangle.
inline bool fullyVisible(const std::vector<MoverView>& views, std::size_t i, const cv::Size& image) {
  const MoverView& v = views[i];
  const cv::Rect2d inside(2, 2, image.width - 4, image.height - 4);
  if (!v.in_front || (v.projected & inside) != v.projected) return false;
  for (std::size_t j = 0; j < views.size(); ++j)
    if (j != i && views[j].distance < v.distance && (views[j].projected & v.projected).area() > 0)
      return false;
  return true;
}

inline double iou(const cv::Rect2d& a, const cv::Rect2d& b) {
  const double inter = (a & b).area();
  return inter / std::max(1e-9, a.area() + b.area() - inter);
}

}  // namespace bmp::test

#include "tracker/temporary_points.hpp"

#include <memory>

#include "tracker/map_point.hpp"

namespace bmp::tracker {

int addTemporaryPoints(Frame& last, const FrameGeometry& g, int max_points) {
  const Features& f = *last.features;
  int considered = 0, made = 0;
  for (int i : f.nearestWithDepth()) {
    if (considered >= max_points) break;
    if (last.isDynamic(i)) continue;
    ++considered;
    if (last.points[i]) continue;
    const Eigen::Vector3d p = last.T_world_cam() * g.camera.backProject(f.un[i], f.depth[i]);
    last.points[i] = std::make_shared<MapPoint>(-1, p, f.descriptors.row(i), -1);
    last.outlier[i] = 0;
    ++made;
  }
  return made;
}

}  // namespace bmp::tracker

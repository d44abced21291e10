#include "tracker/frame_pose.hpp"

#include <limits>

#include "tracker/key_frame.hpp"
#include "tracker/map_point.hpp"
#include "tracker/pose_consensus.hpp"
#include "tracker/pose_optimizer.hpp"

namespace bmp::tracker {

bool isMature(const MapPoint& mp, const PoseOptimizerOptions& options) {
  if (static_cast<int>(mp.observations.size()) < options.mature_observations) return false;
  if (options.mature_span_s <= 0.0) return true;
  if (mp.observations.empty()) return false;  // a temporary point spans no time
  // Observations are ordered by keyframe id, so by time: the first and the last bound the span.
  return mp.observations.rbegin()->first->stamp - mp.observations.begin()->first->stamp >=
         options.mature_span_s;
}

int optimizeFramePose(Frame& frame, const FrameGeometry& g, const PoseOptimizerOptions& options,
                      const PositionPrior* prior, double* position_std_m) {
  const Features& f = *frame.features;
  std::vector<PoseObservation> obs;
  std::vector<int> index;
  for (int i = 0; i < f.size(); ++i) {
    const auto& mp = frame.points[i];
    // A dynamic keypoint keeps its match (its probability travels on) but not its say in the pose.
    if (!mp || mp->bad || f.excluded[i] || frame.isDynamic(i)) {
      frame.outlier[i] = 0;
      continue;
    }
    PoseObservation o;
    o.p_world = mp->p_world;
    o.uv = f.un[i];
    o.u_right = f.uRight(g, i);
    o.information = g.pyramid.inv_sigma2[f.level(i)];
    o.weight = f.weight[i];
    // Points seen by few keyframes are the least proven: new structure, or something that moves.
    if (!isMature(*mp, options)) o.weight *= options.young_point_weight;
    obs.push_back(o);
    index.push_back(i);
  }
  if (obs.size() < 3) {
    if (position_std_m) *position_std_m = std::numeric_limits<double>::infinity();
    return 0;
  }
  SE3 T_cam_world = frame.T_cam_world();
  const PoseCamera camera{g.fx, g.fy, g.cx, g.cy, g.bf};
  T_cam_world = findConsensusPose(T_cam_world, obs, camera, options).T_cam_world;
  const int inliers = optimizePose(T_cam_world, obs, camera, options, prior);
  frame.setPose(T_cam_world.inverse());
  if (position_std_m) *position_std_m = positionStd(T_cam_world, obs, camera);
  for (std::size_t k = 0; k < obs.size(); ++k) frame.outlier[index[k]] = obs[k].outlier ? 1 : 0;
  return inliers;
}

int dropOutliers(Frame& frame) {
  int in_map = 0;
  for (std::size_t i = 0; i < frame.points.size(); ++i) {
    if (!frame.points[i]) continue;
    if (frame.outlier[i] || frame.points[i]->bad) {
      frame.points[i].reset();
      frame.outlier[i] = 0;
    } else if (!frame.points[i]->observations.empty() && !frame.isDynamic(i)) {
      ++in_map;
    }
  }
  return in_map;
}

}  // namespace bmp::tracker

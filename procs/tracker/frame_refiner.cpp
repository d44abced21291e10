#include "tracker/frame_refiner.hpp"

#include "tracker/map_point.hpp"

namespace bmp::tracker {

std::optional<SE3> refineFramePose(const SE3& T_world_cam, const std::vector<RefineObservation>& observations,
                                   const PoseCamera& camera, const PoseOptimizerOptions& options,
                                   double dynamic_threshold, int min_inliers, const PositionPrior* prior) {
  std::vector<PoseObservation> obs;
  obs.reserve(observations.size());
  for (const RefineObservation& o : observations) {
    const std::shared_ptr<MapPoint> mp = o.point.lock();
    // A point found to be on a mover since the frame was tracked no longer speaks for its pose.
    if (!mp || mp->bad || mp->moving_probability > dynamic_threshold) continue;
    PoseObservation p;
    p.p_world = mp->p_world;
    p.uv = o.uv.cast<double>();
    p.u_right = o.u_right;
    p.information = o.information;
    p.weight = o.weight;
    obs.push_back(p);
  }
  if (static_cast<int>(obs.size()) < min_inliers) return std::nullopt;
  SE3 T_cam_world = T_world_cam.inverse();
  const int inliers = optimizePose(T_cam_world, obs, camera, options, prior);
  // Most of the points it was tracked on must still agree: else the map moved under it, keep the old pose.
  if (inliers < min_inliers || 2 * inliers < static_cast<int>(obs.size())) return std::nullopt;
  return T_cam_world.inverse();
}

std::optional<PositionPrior> betweenNeighbours(double t0, const Eigen::Vector3d& c0, double t, double t1,
                                               const Eigen::Vector3d& c1, double accel) {
  if (!(accel > 0.0) || !(t0 < t && t < t1)) return std::nullopt;
  const double s = (t - t0) / (t1 - t0);
  return PositionPrior{c0 + s * (c1 - c0), 0.5 * accel * (t - t0) * (t1 - t)};
}

void FrameRefiner::add(Pending frame) {
  if (enabled()) pending_.push_back(std::move(frame));
}

}  // namespace bmp::tracker

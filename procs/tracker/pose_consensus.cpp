#include "tracker/pose_consensus.hpp"

#include <random>

#include <Eigen/Geometry>

namespace bmp::tracker {

namespace {

double support(const SE3& T, const std::vector<PoseObservation>& obs, const PoseCamera& cam,
               const PoseOptimizerOptions& o) {
  double n = 0;
  for (const auto& ob : obs) {
    if (ob.weight <= 0.0) continue;
    const double limit = o.consensus_chi2_factor * (ob.u_right >= 0.0 ? o.chi2_rgbd : o.chi2_mono);
    const double chi2 = poseChi2(T, ob, cam);
    if (chi2 < limit) n += o.consensus_graded ? ob.weight * (1.0 - chi2 / limit) : ob.weight;
  }
  return n;
}

}  // namespace

ConsensusResult findConsensusPose(const SE3& prior, std::vector<PoseObservation>& obs, const PoseCamera& cam,
                                  const PoseOptimizerOptions& o) {
  ConsensusResult result;
  result.T_cam_world = prior;
  result.prior_support = result.support = support(prior, obs, cam, o);
  // Matches whose depth gives a point in the camera frame.
  std::vector<int> with_depth;
  std::vector<Eigen::Vector3d> p_cam(obs.size());
  for (std::size_t i = 0; i < obs.size(); ++i) {
    const double disparity = obs[i].uv.x() - obs[i].u_right;
    if (obs[i].u_right < 0.0 || disparity <= 0.0 || obs[i].weight <= 0.0) continue;
    const double z = cam.bf / disparity;
    p_cam[i] =
        Eigen::Vector3d((obs[i].uv.x() - cam.cx) / cam.fx * z, (obs[i].uv.y() - cam.cy) / cam.fy * z, z);
    with_depth.push_back(static_cast<int>(i));
  }
  if (with_depth.size() >= 6 && o.consensus_iterations > 0) {
    std::mt19937 rng(12345u + static_cast<unsigned>(obs.size()));
    std::uniform_int_distribution<std::size_t> pick(0, with_depth.size() - 1);
    for (int it = 0; it < o.consensus_iterations; ++it) {
      const int a = with_depth[pick(rng)], b = with_depth[pick(rng)], c = with_depth[pick(rng)];
      if (a == b || b == c || a == c) continue;
      // Reject near-collinear samples: their rotation is undetermined.
      const Eigen::Vector3d& wa = obs[a].p_world;
      if ((obs[b].p_world - wa).cross(obs[c].p_world - wa).norm() < 1e-3) continue;
      Eigen::Matrix3d src, dst;
      src << obs[a].p_world, obs[b].p_world, obs[c].p_world;
      dst << p_cam[a], p_cam[b], p_cam[c];
      SE3 T;
      T.matrix() = Eigen::umeyama(src, dst, false);
      const double s = support(T, obs, cam, o);
      if (s > result.support) {
        result.support = s;
        result.T_cam_world = T;
        result.from_sample = true;
      }
    }
  }
  for (auto& ob : obs) {
    const double limit = o.consensus_chi2_factor * (ob.u_right >= 0.0 ? o.chi2_rgbd : o.chi2_mono);
    ob.outlier = poseChi2(result.T_cam_world, ob, cam) >= limit;
  }
  return result;
}

}  // namespace bmp::tracker

#include "tracker/pose_optimizer.hpp"

#include <ceres/ceres.h>

#include <cmath>

#include "tracker/pose_params.hpp"
#include "tracker/residuals.hpp"

namespace bmp::tracker {

namespace {

PinholeBf toPinhole(const PoseCamera& c) {
  return {c.fx, c.fy, c.cx, c.cy, c.bf};
}

}  // namespace

double poseChi2(const SE3& T, const PoseObservation& o, const PoseCamera& c) {
  const Eigen::Vector3d p = T * o.p_world;
  if (p.z() <= 0.0) return 1e12;
  const double u = c.fx * p.x() / p.z() + c.cx, v = c.fy * p.y() / p.z() + c.cy;
  double e2 = (u - o.uv.x()) * (u - o.uv.x()) + (v - o.uv.y()) * (v - o.uv.y());
  if (o.u_right >= 0.0) {
    const double ur = u - c.bf / p.z();
    e2 += (ur - o.u_right) * (ur - o.u_right);
  }
  return e2 * o.information;
}

int optimizePose(SE3& T_cam_world, std::vector<PoseObservation>& obs, const PoseCamera& camera,
                 const PoseOptimizerOptions& options) {
  double pose[6];
  poseToParams(T_cam_world, pose);
  const PinholeBf cam = toPinhole(camera);
  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::DENSE_QR;
  solver.max_num_iterations = options.iterations_per_round;
  solver.num_threads = 1;
  solver.logging_type = ceres::SILENT;
  int inliers = 0;
  for (int round = 0; round < options.rounds; ++round) {
    ceres::Problem problem;
    int residuals = 0;
    const bool robust = round + 1 < options.rounds;  // the last round refines on inliers only
    for (const auto& o : obs) {
      if (o.outlier || o.weight <= 0.0) continue;
      const double s = std::sqrt(o.information * o.weight);
      ceres::CostFunction* cost = nullptr;
      double delta = 0.0;
      if (o.u_right >= 0.0) {
        cost = new ceres::AutoDiffCostFunction<PoseOnlyError<3>, 3, 6>(
            new PoseOnlyError<3>(cam, o.p_world, o.uv, o.u_right, s));
        delta = std::sqrt(options.chi2_rgbd);
      } else {
        cost = new ceres::AutoDiffCostFunction<PoseOnlyError<2>, 2, 6>(
            new PoseOnlyError<2>(cam, o.p_world, o.uv, 0.0, s));
        delta = std::sqrt(options.chi2_mono);
      }
      problem.AddResidualBlock(cost, robust ? new ceres::HuberLoss(delta) : nullptr, pose);
      ++residuals;
    }
    if (residuals < 3) break;
    ceres::Solver::Summary summary;
    ceres::Solve(solver, &problem, &summary);
    // Reclassify every observation, so a point wrongly rejected early can return.
    const SE3 T = poseFromParams(pose);
    inliers = 0;
    for (auto& o : obs) {
      const double chi2 = poseChi2(T, o, camera);
      o.outlier = chi2 > (o.u_right >= 0.0 ? options.chi2_rgbd : options.chi2_mono);
      if (!o.outlier && o.weight > 0.0) ++inliers;
    }
    if (inliers < 10) break;
  }
  T_cam_world = normalized(poseFromParams(pose));
  return inliers;
}

}  // namespace bmp::tracker

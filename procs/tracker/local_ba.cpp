#include "tracker/local_ba.hpp"

#include <ceres/ceres.h>

#include <cmath>

#include "tracker/pose_params.hpp"
#include "tracker/residuals.hpp"

namespace bmp::tracker {

namespace {

// A keyframe pose from its parameters, re-orthonormalised (many small BA steps must not drift off SO(3)).
SE3 baPose(const double* pose) {
  return normalized(poseFromParams(pose));
}

double chi2Of(const double* pose, const double* p, const BaObservation& o, const PoseCamera& c) {
  PoseObservation po;
  po.p_world = Eigen::Vector3d(p[0], p[1], p[2]);
  po.uv = o.uv;
  po.u_right = o.u_right;
  po.information = o.information;
  return poseChi2(baPose(pose), po, c);
}

bool behindCamera(const double* pose, const double* p) {
  return (baPose(pose) * Eigen::Vector3d(p[0], p[1], p[2])).z() <= 0.0;
}

}  // namespace

BaSummary solveLocalBa(BaProblem& ba, const PoseCamera& camera, const MappingOptions& mapping,
                       const PoseOptimizerOptions& th) {
  BaSummary summary;
  std::vector<double> poses(ba.keyframes.size() * 6);
  std::vector<double> points(ba.points.size() * 3);
  for (std::size_t k = 0; k < ba.keyframes.size(); ++k)
    poseToParams(ba.keyframes[k].T_cam_world, &poses[6 * k]);
  for (std::size_t i = 0; i < ba.points.size(); ++i)
    for (int j = 0; j < 3; ++j) points[3 * i + j] = ba.points[i].p_world[j];
  const PinholeBf cam{camera.fx, camera.fy, camera.cx, camera.cy, camera.bf};

  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::SPARSE_SCHUR;
  // Eigen's sparse Cholesky: no OpenMP threads of CHOLMOD competing with tracking on a small machine.
  solver.sparse_linear_algebra_library_type = ceres::EIGEN_SPARSE;
  solver.num_threads = 1;
  solver.logging_type = ceres::SILENT;

  for (int stage = 0; stage < 2; ++stage) {
    ceres::Problem problem;
    int residuals = 0;
    for (const auto& o : ba.observations) {
      if (o.outlier || o.weight <= 0.0) continue;
      double* pose = &poses[6 * o.keyframe];
      double* p = &points[3 * o.point];
      const double s = std::sqrt(o.information * o.weight);
      if (o.u_right >= 0.0) {
        problem.AddResidualBlock(new ceres::AutoDiffCostFunction<BundleError<3>, 3, 6, 3>(
                                     new BundleError<3>(cam, o.uv, o.u_right, s)),
                                 new ceres::HuberLoss(std::sqrt(th.chi2_rgbd)), pose, p);
      } else {
        problem.AddResidualBlock(
            new ceres::AutoDiffCostFunction<BundleError<2>, 2, 6, 3>(new BundleError<2>(cam, o.uv, 0.0, s)),
            new ceres::HuberLoss(std::sqrt(th.chi2_mono)), pose, p);
      }
      ++residuals;
    }
    if (residuals == 0) break;
    for (std::size_t k = 0; k < ba.keyframes.size(); ++k)
      if (ba.keyframes[k].fixed && problem.HasParameterBlock(&poses[6 * k]))
        problem.SetParameterBlockConstant(&poses[6 * k]);
    solver.max_num_iterations = stage == 0 ? mapping.ba_iterations_first : mapping.ba_iterations_second;
    ceres::Solver::Summary s;
    ceres::Solve(solver, &problem, &s);
    if (stage == 0) {
      summary.initial_cost = s.initial_cost;
      summary.residuals = residuals;
    }
    summary.final_cost = s.final_cost;
    for (auto& o : ba.observations) {
      const double* pose = &poses[6 * o.keyframe];
      const double* p = &points[3 * o.point];
      const double limit = o.u_right >= 0.0 ? th.chi2_rgbd : th.chi2_mono;
      o.outlier = behindCamera(pose, p) || chi2Of(pose, p, o, camera) > limit;
    }
  }
  summary.outliers = 0;
  for (const auto& o : ba.observations) summary.outliers += o.outlier;
  for (std::size_t k = 0; k < ba.keyframes.size(); ++k)
    if (!ba.keyframes[k].fixed) ba.keyframes[k].T_cam_world = baPose(&poses[6 * k]);
  for (std::size_t i = 0; i < ba.points.size(); ++i)
    ba.points[i].p_world = Eigen::Vector3d(points[3 * i], points[3 * i + 1], points[3 * i + 2]);
  return summary;
}

}  // namespace bmp::tracker

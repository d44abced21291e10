#include "tracker/pose_optimizer.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/LU>

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace bmp::tracker {

namespace {

// A 6-DoF Levenberg-Marquardt on the pose alone, with Huber weights (IRLS). The problem is tiny (6 unknowns,
// a few hundred residuals), so the normal equations are built directly: no solver object, no allocation per
// residual, which is where a general solver spent most of this step's time.
using Mat6 = Eigen::Matrix<double, 6, 6>;
using Vec6 = Eigen::Matrix<double, 6, 1>;

struct Active {
  const PoseObservation* obs;
  double sqrt_info;  // sqrt(information): whitens the residual
  // Scales the robust cost. Folded into the whitening it would move the Huber threshold too: a young
  // point's (weight 0.05) would sit 4.5 times further out, and a group of them moving together would pull
  // the pose unchecked.
  double weight;
  double delta2;  // Huber threshold on the squared whitened residual; <= 0: plain least squares
};

// Whitened residual (2 or 3 rows) and its Jacobian with respect to a left increment (omega, v) of the pose:
// p' = exp(omega) p + v, so dp/d(omega, v) = [-[p]x | I]. Returns the rows, 0 when the point is behind the
// camera.
int residualAndJacobian(const SE3& T, const Active& a, const PoseCamera& c, double* r,
                        Eigen::Matrix<double, 3, 6>* J) {
  const Eigen::Vector3d p = T * a.obs->p_world;
  if (p.z() <= 0.0) return 0;
  const double inv_z = 1.0 / p.z();
  const double u = c.fx * p.x() * inv_z + c.cx, v = c.fy * p.y() * inv_z + c.cy;
  const int rows = a.obs->u_right >= 0.0 ? 3 : 2;
  r[0] = a.sqrt_info * (u - a.obs->uv.x());
  r[1] = a.sqrt_info * (v - a.obs->uv.y());
  if (rows == 3) r[2] = a.sqrt_info * (u - c.bf * inv_z - a.obs->u_right);
  if (J == nullptr) return rows;
  Eigen::Matrix<double, 3, 3> dproj;
  dproj << c.fx * inv_z, 0.0, -c.fx * p.x() * inv_z * inv_z,  //
      0.0, c.fy * inv_z, -c.fy * p.y() * inv_z * inv_z,       //
      c.fx * inv_z, 0.0, (-c.fx * p.x() + c.bf) * inv_z * inv_z;
  Eigen::Matrix<double, 3, 6> dp;
  dp << 0.0, p.z(), -p.y(), 1.0, 0.0, 0.0,  //
      -p.z(), 0.0, p.x(), 0.0, 1.0, 0.0,    //
      p.y(), -p.x(), 0.0, 0.0, 0.0, 1.0;
  *J = a.sqrt_info * dproj * dp;
  return rows;
}

// Huber cost of a squared residual s, as Ceres's HuberLoss: s inside, 2 delta sqrt(s) - delta^2 outside.
double huber(double s, double delta2) {
  if (delta2 <= 0.0 || s <= delta2) return s;
  return 2.0 * std::sqrt(delta2 * s) - delta2;
}

double huberWeight(double s, double delta2) {
  if (delta2 <= 0.0 || s <= delta2) return 1.0;
  return std::sqrt(delta2 / s);
}

// A solve that ends with its position this far from the prior (squared, in sigmas) is redone without it.
constexpr double kPriorGateChi2 = 16.27;  // 99.9 % chi-square, 3 dof

// The camera centre c = -R^T t. Under a left increment (omega, v) it moves by -R^T v (to first order; omega
// turns it about itself), so the prior's Jacobian is [0 | -R^T] / sigma.
Eigen::Vector3d priorError(const SE3& T, const PositionPrior& prior) {
  return (-(T.rotation().transpose() * T.translation()) - prior.center) / prior.sigma_m;
}

double totalCost(const SE3& T, const std::vector<Active>& active, const PoseCamera& c,
                 const PositionPrior* prior) {
  double cost = prior != nullptr ? priorError(T, *prior).squaredNorm() : 0.0;
  double r[3];
  for (const auto& a : active) {
    const int rows = residualAndJacobian(T, a, c, r, nullptr);
    if (rows == 0) return INFINITY;  // a step that puts a point behind the camera is refused
    double s = 0.0;
    for (int i = 0; i < rows; ++i) s += r[i] * r[i];
    cost += a.weight * huber(s, a.delta2);
  }
  return cost;
}

SE3 applyIncrement(const SE3& T, const Vec6& d) {
  const Eigen::Vector3d w = d.head<3>();
  const double angle = w.norm();
  SE3 out = T;
  if (angle > 1e-15) {
    const Eigen::Matrix3d R = Eigen::AngleAxisd(angle, w / angle).toRotationMatrix();
    out.linear() = R * T.linear();
    out.translation() = R * T.translation();
  }
  out.translation() += d.tail<3>();
  return out;
}

void levenbergMarquardt(SE3& T, const std::vector<Active>& active, const PoseCamera& c, int iterations,
                        const PositionPrior* prior) {
  double cost = totalCost(T, active, c, prior);
  double lambda = 1e-4;
  double r[3];
  Eigen::Matrix<double, 3, 6> J;
  for (int it = 0; it < iterations; ++it) {
    Mat6 H = Mat6::Zero();
    Vec6 g = Vec6::Zero();
    for (const auto& a : active) {
      const int rows = residualAndJacobian(T, a, c, r, &J);
      double s = 0.0;
      for (int i = 0; i < rows; ++i) s += r[i] * r[i];
      const double w = a.weight * huberWeight(s, a.delta2);
      // Fixed sizes: a dynamic block here costs a general matrix product per residual.
      if (rows == 3) {
        H.noalias() += w * J.transpose() * J;
        g.noalias() += w * J.transpose() * Eigen::Map<const Eigen::Vector3d>(r);
      } else if (rows == 2) {
        const auto J2 = J.topRows<2>();
        H.noalias() += w * J2.transpose() * J2;
        g.noalias() += w * J2.transpose() * Eigen::Map<const Eigen::Vector2d>(r);
      }
    }
    if (prior != nullptr) {  // J^T J = I / sigma^2 on the translation block, whatever R is
      const double info = 1.0 / (prior->sigma_m * prior->sigma_m);
      H.diagonal().tail<3>().array() += info;
      g.tail<3>() -= T.rotation() * priorError(T, *prior) / prior->sigma_m;
    }
    bool improved = false;
    for (int attempt = 0; attempt < 10 && !improved; ++attempt) {
      Mat6 A = H;
      A.diagonal() += lambda * H.diagonal().cwiseMax(1e-9);
      const Vec6 d = A.ldlt().solve(-g);
      if (!d.allFinite()) break;
      const SE3 candidate = applyIncrement(T, d);
      const double candidate_cost = totalCost(candidate, active, c, prior);
      if (candidate_cost < cost) {
        const double gain = cost - candidate_cost;
        T = candidate;
        cost = candidate_cost;
        lambda = std::max(lambda / 10.0, 1e-9);
        improved = true;
        if (gain < 1e-10 * cost || d.norm() < 1e-12) return;  // converged
      } else {
        lambda *= 10.0;
      }
    }
    if (!improved) return;  // no step lowers the cost: at a minimum
  }
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

namespace {

// Rounds of optimisation and outlier classification from T; returns the inliers.
int solveRounds(SE3& T, std::vector<PoseObservation>& obs, const PoseCamera& camera,
                const PoseOptimizerOptions& options, const PositionPrior* prior) {
  std::vector<Active> active;
  active.reserve(obs.size());
  int inliers = 0;
  for (int round = 0; round < options.rounds; ++round) {
    const bool robust = round + 1 < options.rounds;  // the last round refines on inliers only
    active.clear();
    for (const auto& o : obs) {
      if (o.outlier || o.weight <= 0.0) continue;
      if ((T * o.p_world).z() <= 0.0) continue;  // behind the camera: no residual; classified below
      const double delta2 = robust ? (o.u_right >= 0.0 ? options.chi2_rgbd : options.chi2_mono) : 0.0;
      active.push_back({&o, std::sqrt(o.information), o.weight, delta2});
    }
    if (active.size() < 3) break;
    levenbergMarquardt(T, active, camera, options.iterations_per_round, prior);
    // Reclassify every observation, so a point wrongly rejected early can return.
    inliers = 0;
    for (auto& o : obs) {
      const double chi2 = poseChi2(T, o, camera);
      o.outlier = chi2 > (o.u_right >= 0.0 ? options.chi2_rgbd : options.chi2_mono);
      if (!o.outlier && o.weight > 0.0) ++inliers;
    }
    if (inliers < 10) break;
  }
  return inliers;
}

}  // namespace

double positionStd(const SE3& T, const std::vector<PoseObservation>& obs, const PoseCamera& camera) {
  // A weighted least-squares estimate: its covariance is A^-1 B A^-1 with A = sum w J^T J (what the solve
  // inverts) and B = sum w^2 J^T J (the noise each residual brings), so a down-weighted young point adds its
  // little information, no more, no less.
  Mat6 A = Mat6::Zero(), B = Mat6::Zero();
  double r[3];
  Eigen::Matrix<double, 3, 6> J;
  int used = 0;
  for (const auto& o : obs) {
    if (o.outlier || o.weight <= 0.0) continue;
    const Active a{&o, std::sqrt(o.information), o.weight, 0.0};
    const int rows = residualAndJacobian(T, a, camera, r, &J);
    if (rows == 0) continue;
    const Mat6 JtJ = J.topRows(rows).transpose() * J.topRows(rows);
    A.noalias() += o.weight * JtJ;
    B.noalias() += o.weight * o.weight * JtJ;
    ++used;
  }
  if (used < 3) return std::numeric_limits<double>::infinity();
  const Eigen::FullPivLU<Mat6> lu(A);
  if (!lu.isInvertible()) return std::numeric_limits<double>::infinity();
  const Mat6 A_inv = lu.inverse();
  // The centre c = -R^T t moves by -R^T v under the increment (omega, v): its covariance is the translation
  // block's turned by R^T, with the same eigenvalues.
  const Eigen::Matrix3d C = (A_inv * B * A_inv).bottomRightCorner<3, 3>();
  const double worst =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(0.5 * (C + C.transpose())).eigenvalues()(2);
  return worst > 0.0 && std::isfinite(worst) ? std::sqrt(worst) : std::numeric_limits<double>::infinity();
}

int optimizePose(SE3& T_cam_world, std::vector<PoseObservation>& obs, const PoseCamera& camera,
                 const PoseOptimizerOptions& options, const PositionPrior* prior) {
  if (prior != nullptr && !(prior->sigma_m > 0.0)) prior = nullptr;
  SE3 T = T_cam_world;
  std::vector<uint8_t> initial_outliers;
  if (prior != nullptr)
    for (const auto& o : obs) initial_outliers.push_back(o.outlier ? 1 : 0);
  int inliers = solveRounds(T, obs, camera, options, prior);
  // A pose the prediction cannot explain (the camera did accelerate): the prior would drag it and push its
  // matches out as outliers. Solved again without it.
  if (prior != nullptr && priorError(T, *prior).squaredNorm() > kPriorGateChi2) {
    for (std::size_t k = 0; k < obs.size(); ++k) obs[k].outlier = initial_outliers[k] != 0;
    T = T_cam_world;
    inliers = solveRounds(T, obs, camera, options, nullptr);
  }
  T_cam_world = normalized(T);
  return inliers;
}

}  // namespace bmp::tracker

#include "eval/body_offset.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/SVD>

namespace bmp::eval {

namespace {

constexpr double kMinAngleDeg = 10.0;  // smaller offsets are within what a tracker's own error may show
constexpr std::size_t kMinPairs = 10;

// The pose whose stamp is t (the association's stamps come from these very trajectories).
const StampedPose* atStamp(const Trajectory& trajectory, double t) {
  const auto it = std::lower_bound(trajectory.begin(), trajectory.end(), t - 1e-9,
                                   [](const StampedPose& p, double s) { return p.stamp < s; });
  if (it == trajectory.end() || std::abs(it->stamp - t) > 1e-6) return nullptr;
  return &*it;
}

double angleDeg(const Eigen::Matrix3d& R) {
  const double c = std::clamp((R.trace() - 1.0) / 2.0, -1.0, 1.0);
  return std::acos(c) * 180.0 / M_PI;
}

}  // namespace

bool BodyOffset::constant() const {
  return pairs >= kMinPairs && angle_deg > kMinAngleDeg && spread_deg < angle_deg / 4.0;
}

BodyOffset measureBodyOffset(const Trajectory& gt, const Trajectory& est, const AteResult& ate,
                             double est_offset) {
  std::vector<Eigen::Matrix3d> offsets;
  for (const AtePair& pair : ate.pairs) {
    const StampedPose* g = atStamp(gt, pair.gt_stamp);
    const StampedPose* e = atStamp(est, pair.est_stamp);
    if (!e) e = atStamp(est, pair.est_stamp - est_offset);
    if (!g || !e) continue;
    // R_gt = R_align * R_est * B  =>  B = (R_align * R_est)^T * R_gt
    offsets.push_back((ate.alignment.rotation * e->T_world_cam.rotation()).transpose() *
                      g->T_world_cam.rotation());
  }
  BodyOffset out;
  out.pairs = offsets.size();
  if (offsets.empty()) return out;
  // Chordal mean: the rotation nearest the sum of the matrices.
  Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
  for (const auto& B : offsets) sum += B;
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(sum, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d mean = svd.matrixU() * svd.matrixV().transpose();
  if (mean.determinant() < 0) {
    Eigen::Matrix3d flip = Eigen::Matrix3d::Identity();
    flip(2, 2) = -1.0;
    mean = svd.matrixU() * flip * svd.matrixV().transpose();
  }
  out.angle_deg = angleDeg(mean);
  std::vector<double> spread;
  spread.reserve(offsets.size());
  for (const auto& B : offsets) spread.push_back(angleDeg(mean.transpose() * B));
  std::nth_element(spread.begin(), spread.begin() + spread.size() / 2, spread.end());
  out.spread_deg = spread[spread.size() / 2];
  return out;
}

}  // namespace bmp::eval

#include "tracker/trajectory_eval.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include <Eigen/Geometry>

namespace bmp::tracker {

AteResult computeAte(const Trajectory& est, const Trajectory& gt, double max_dt) {
  std::vector<Eigen::Vector3d> a, b;
  for (const auto& e : est) {
    const auto it = std::lower_bound(gt.begin(), gt.end(), e.stamp,
                                     [](const StampedPose& p, double t) { return p.stamp < t; });
    const StampedPose* best = nullptr;
    if (it != gt.end()) best = &*it;
    if (it != gt.begin() &&
        (!best || std::abs(std::prev(it)->stamp - e.stamp) < std::abs(best->stamp - e.stamp)))
      best = &*std::prev(it);
    if (!best || std::abs(best->stamp - e.stamp) > max_dt) continue;
    a.push_back(e.T_world_cam.translation());
    b.push_back(best->T_world_cam.translation());
  }
  if (a.size() < 3) throw std::runtime_error("ATE: fewer than 3 associated poses");
  Eigen::Matrix3Xd src(3, a.size()), dst(3, b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    src.col(static_cast<Eigen::Index>(i)) = a[i];
    dst.col(static_cast<Eigen::Index>(i)) = b[i];
  }
  AteResult r;
  r.T_gt_est.matrix() = Eigen::umeyama(src, dst, false);
  std::vector<double> errors(a.size());
  double sum2 = 0.0, sum = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    errors[i] = (r.T_gt_est * a[i] - b[i]).norm();
    sum2 += errors[i] * errors[i];
    sum += errors[i];
  }
  r.matched = static_cast<int>(a.size());
  r.rmse = std::sqrt(sum2 / a.size());
  r.mean = sum / a.size();
  r.max = *std::max_element(errors.begin(), errors.end());
  std::nth_element(errors.begin(), errors.begin() + errors.size() / 2, errors.end());
  r.median = errors[errors.size() / 2];
  return r;
}

}  // namespace bmp::tracker

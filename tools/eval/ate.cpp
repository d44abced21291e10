#include "eval/ate.hpp"

#include <sstream>

#include "eval/eval_error.hpp"

namespace bmp::eval {

namespace {
std::vector<double> stampsOf(const Trajectory& trajectory) {
  std::vector<double> stamps;
  stamps.reserve(trajectory.size());
  for (const auto& pose : trajectory) stamps.push_back(pose.stamp);
  return stamps;
}
}  // namespace

AteResult computeAte(const Trajectory& gt, const Trajectory& est, const AteOptions& options) {
  const std::vector<Match> matches =
      associate(stampsOf(gt), stampsOf(est), options.offset, options.max_difference);
  // evaluate_ate.py also stops below two pairs: one pair always aligns perfectly.
  if (matches.size() < 2) {
    std::ostringstream msg;
    msg << (matches.empty() ? "no estimated stamp lies" : "only one estimated stamp lies") << " within "
        << options.max_difference << " s of a ground-truth stamp (offset " << options.offset << " s)";
    if (!gt.empty() && !est.empty()) {
      msg.precision(15);
      msg << "; ground truth spans " << gt.front().stamp << ".." << gt.back().stamp << ", estimate "
          << est.front().stamp << ".." << est.back().stamp;
    }
    throw EvalError(msg.str());
  }
  const auto n = static_cast<Eigen::Index>(matches.size());
  Eigen::Matrix3Xd model(3, n);
  Eigen::Matrix3Xd data(3, n);
  for (Eigen::Index k = 0; k < n; ++k) {
    const Match& m = matches[static_cast<std::size_t>(k)];
    model.col(k) = est[m.second].T_world_cam.translation() * options.scale;
    data.col(k) = gt[m.first].T_world_cam.translation();
  }
  AteResult result;
  result.alignment = alignHorn(model, data);
  std::vector<double> errors;
  errors.reserve(matches.size());
  for (Eigen::Index k = 0; k < n; ++k) {
    const Match& m = matches[static_cast<std::size_t>(k)];
    AtePair pair;
    pair.gt_stamp = gt[m.first].stamp;
    pair.est_stamp = est[m.second].stamp;
    pair.gt_position = data.col(k);
    pair.aligned_position = result.alignment.apply(model.col(k));
    pair.error = (pair.aligned_position - pair.gt_position).norm();
    errors.push_back(pair.error);
    result.pairs.push_back(pair);
  }
  result.stats = computeStats(errors);
  return result;
}

Trajectory alignedTrajectory(const Trajectory& est, const RigidAlignment& alignment, double scale) {
  Trajectory out = est;
  for (auto& pose : out) {
    const Eigen::Vector3d p = alignment.apply(pose.T_world_cam.translation() * scale);
    pose.T_world_cam.linear() = alignment.rotation * pose.T_world_cam.linear();
    pose.T_world_cam.translation() = p;
  }
  return out;
}

}  // namespace bmp::eval

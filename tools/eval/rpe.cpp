#include "eval/rpe.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/LU>

#include "eval/eval_error.hpp"

namespace bmp::eval {

std::size_t findClosestIndex(const std::vector<double>& L, double t) {
  std::size_t beginning = 0;
  double difference = std::abs(L[0] - t);
  std::size_t best = 0;
  std::size_t end = L.size();
  while (beginning < end) {
    const std::size_t middle = (end + beginning) / 2;
    if (std::abs(L[middle] - t) < difference) {
      difference = std::abs(L[middle] - t);
      best = middle;
    }
    if (t == L[middle]) return middle;
    if (L[middle] > t) {
      end = middle;
    } else {
      beginning = middle + 1;
    }
  }
  return best;
}

DeltaUnit parseDeltaUnit(const std::string& text) {
  if (text == "s") return DeltaUnit::kSeconds;
  if (text == "f") return DeltaUnit::kFrames;
  throw EvalError("unknown RPE delta unit '" + text + "' (use s for seconds or f for frames)");
}

const char* deltaUnitName(DeltaUnit unit) {
  return unit == DeltaUnit::kSeconds ? "s" : "f";
}

namespace {
Eigen::Matrix4d matrixOf(const SE3& T) {
  return T.matrix();
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t mid = v.size() / 2;
  return v.size() % 2 == 1 ? v[mid] : 0.5 * (v[mid - 1] + v[mid]);
}
}  // namespace

RpeResult computeRpe(const Trajectory& gt, const Trajectory& est, const RpeOptions& options) {
  RpeResult result;
  if (gt.size() < 2 || est.size() < 2) return result;
  std::vector<double> stamps_gt;
  std::vector<double> stamps_est;
  for (const auto& p : gt) stamps_gt.push_back(p.stamp);
  for (const auto& p : est) stamps_est.push_back(p.stamp);

  std::vector<double> index_est;
  if (options.unit == DeltaUnit::kSeconds) {
    index_est = stamps_est;
  } else {
    for (std::size_t k = 0; k < est.size(); ++k) index_est.push_back(static_cast<double>(k));
  }
  const std::size_t n = est.size();
  std::vector<std::pair<std::size_t, std::size_t>> index_pairs;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = findClosestIndex(index_est, index_est[i] + options.delta);
    if (j != n - 1) index_pairs.emplace_back(i, j);
  }

  std::vector<double> gaps;
  for (std::size_t k = 1; k < stamps_gt.size(); ++k) gaps.push_back(stamps_gt[k] - stamps_gt[k - 1]);
  result.gt_interval = median(gaps);
  const double max_dt = 2 * result.gt_interval;

  std::vector<double> trans;
  std::vector<double> rot;
  for (const auto& [i, j] : index_pairs) {
    RpePair pair;
    pair.i = i;
    pair.j = j;
    pair.est_stamp_0 = stamps_est[i];
    pair.est_stamp_1 = stamps_est[j];
    const std::size_t g0 = findClosestIndex(stamps_gt, pair.est_stamp_0 + options.offset);
    const std::size_t g1 = findClosestIndex(stamps_gt, pair.est_stamp_1 + options.offset);
    pair.gt_stamp_0 = stamps_gt[g0];
    pair.gt_stamp_1 = stamps_gt[g1];
    if (std::abs(pair.gt_stamp_0 - (pair.est_stamp_0 + options.offset)) > max_dt ||
        std::abs(pair.gt_stamp_1 - (pair.est_stamp_1 + options.offset)) > max_dt) {
      continue;
    }
    // 4x4 matrices with general inverses, as the script does, so results agree to rounding.
    Eigen::Matrix4d est_back = matrixOf(est[j].T_world_cam).inverse() * matrixOf(est[i].T_world_cam);
    est_back.block<3, 1>(0, 3) *= options.scale;
    const Eigen::Matrix4d gt_back = matrixOf(gt[g1].T_world_cam).inverse() * matrixOf(gt[g0].T_world_cam);
    const Eigen::Matrix4d error = est_back.inverse() * gt_back;
    pair.trans_error = error.block<3, 1>(0, 3).norm();
    const double c = (error.block<3, 3>(0, 0).trace() - 1) / 2;
    pair.rot_error = std::acos(std::clamp(c, -1.0, 1.0));
    trans.push_back(pair.trans_error);
    rot.push_back(pair.rot_error);
    result.pairs.push_back(pair);
  }
  result.trans = computeStats(trans);
  result.rot_deg = scaled(computeStats(rot), 180.0 / M_PI);
  return result;
}

}  // namespace bmp::eval

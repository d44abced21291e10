#include "tracker/map_point.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "tracker/frame.hpp"
#include "tracker/key_frame.hpp"

namespace bmp::tracker {

bool KeyFrameIdLess::operator()(const KeyFrame* a, const KeyFrame* b) const {
  return a->id < b->id;
}

MapPoint::MapPoint(int64_t i, const Eigen::Vector3d& p, const cv::Mat& d, int64_t first)
    : id(i), p_world(p), descriptor(d.clone()), first_kf_id(first) {}

int MapPoint::predictLevel(double distance, const FrameGeometry& g) const {
  if (distance <= 0.0) return 0;
  const int level = static_cast<int>(std::ceil(std::log(max_distance / distance) / g.pyramid.log_factor));
  return std::clamp(level, 0, g.pyramid.levels - 1);
}

void MapPoint::initGeometry(const Eigen::Vector3d& camera_center, int level, const FrameGeometry& g) {
  const Eigen::Vector3d ray = p_world - camera_center;
  const double dist = ray.norm();
  normal = ray / std::max(dist, 1e-9);
  max_distance = dist * g.pyramid.scale[level];
  min_distance = max_distance / g.pyramid.scale[g.pyramid.levels - 1];
}

void MapPoint::updateNormalAndDepth(const FrameGeometry& g) {
  if (bad || observations.empty()) return;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const auto& [kf, idx] : observations) {
    (void)idx;
    sum += (p_world - kf->center()).normalized();
  }
  if (reference == nullptr || observations.count(reference) == 0) reference = observations.begin()->first;
  const int level = reference->features->level(observations.at(reference));
  const double dist = (p_world - reference->center()).norm();
  max_distance = dist * g.pyramid.scale[level];
  min_distance = max_distance / g.pyramid.scale[g.pyramid.levels - 1];
  normal = sum.normalized();
}

void MapPoint::updateDescriptor() {
  if (bad || observations.empty()) return;
  std::vector<const uint8_t*> descs;
  descs.reserve(observations.size());
  for (const auto& [kf, idx] : observations) descs.push_back(kf->features->descriptor(idx));
  const std::size_t n = descs.size();
  std::size_t best = 0;
  int best_median = 257;
  std::vector<int> row(n);
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = 0; j < n; ++j) row[j] = i == j ? 0 : hamming(descs[i], descs[j]);
    std::nth_element(row.begin(), row.begin() + (n - 1) / 2, row.end());
    const int median = row[(n - 1) / 2];
    if (median < best_median) {
      best_median = median;
      best = i;
    }
  }
  std::copy(descs[best], descs[best] + 32, descriptor.ptr<uint8_t>(0));
}

}  // namespace bmp::tracker

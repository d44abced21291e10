#include "mapper/floor_plane.hpp"

#include <Eigen/Eigenvalues>

#include <cmath>
#include <random>
#include <vector>

namespace bmp::mapper {

namespace {

// Every k-th point, at most max_points of them: the fit's cost stays fixed as the map grows.
std::vector<Eigen::Vector3d> sample(const PointList& cloud, int max_points) {
  const std::size_t step = std::max<std::size_t>(1, cloud.size() / static_cast<std::size_t>(max_points));
  std::vector<Eigen::Vector3d> out;
  out.reserve(cloud.size() / step + 1);
  for (std::size_t i = 0; i < cloud.size(); i += step) out.push_back(cloud[i].position().cast<double>());
  return out;
}

// Least-squares plane through the points within inlier_m of `plane` (normal kept on up's side).
FloorPlane refine(const std::vector<Eigen::Vector3d>& pts, const FloorPlane& plane, double inlier_m,
                  const Eigen::Vector3d& up) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  std::vector<const Eigen::Vector3d*> support;
  for (const auto& p : pts)
    if (std::abs(plane.normal.dot(p) - plane.height) < inlier_m) support.push_back(&p);
  if (support.size() < 3) return plane;
  for (const auto* p : support) mean += *p;
  mean /= static_cast<double>(support.size());
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const auto* p : support) cov += (*p - mean) * (*p - mean).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  FloorPlane out = plane;
  out.normal = eig.eigenvectors().col(0);  // smallest eigenvalue: the plane's normal
  if (out.normal.dot(up) < 0) out.normal = -out.normal;
  out.height = out.normal.dot(mean);
  out.share = static_cast<double>(support.size()) / static_cast<double>(pts.size());
  return out;
}

// The plane within acos(min_cos) of `up` that most of pts support (at least min_support), by RANSAC.
std::optional<FloorPlane> largestPlane(const std::vector<Eigen::Vector3d>& pts, const Eigen::Vector3d& up,
                                       double min_cos, std::size_t min_support, const FloorSettings& s,
                                       std::mt19937& rng) {
  if (pts.size() < 3) return std::nullopt;
  std::uniform_int_distribution<std::size_t> pick(0, pts.size() - 1);
  std::optional<FloorPlane> best;
  std::size_t best_support = 0;
  for (int it = 0; it < s.iterations; ++it) {
    const Eigen::Vector3d& a = pts[pick(rng)];
    const Eigen::Vector3d n = (pts[pick(rng)] - a).cross(pts[pick(rng)] - a);
    if (n.norm() < 1e-9) continue;
    FloorPlane plane;
    plane.normal = n.normalized();
    if (plane.normal.dot(up) < 0) plane.normal = -plane.normal;
    if (plane.normal.dot(up) < min_cos) continue;
    plane.height = plane.normal.dot(a);
    std::size_t support = 0;
    for (const auto& p : pts) support += std::abs(plane.normal.dot(p) - plane.height) < s.inlier_m;
    if (support >= min_support && support > best_support) {
      best = plane;
      best_support = support;
    }
  }
  return best;
}

}  // namespace

std::optional<FloorPlane> fitFloor(const PointList& cloud, const Eigen::Vector3d& up_in,
                                   const FloorSettings& s) {
  const std::vector<Eigen::Vector3d> pts = sample(cloud, s.max_points);
  if (pts.size() < 100) return std::nullopt;
  const Eigen::Vector3d up = up_in.normalized();
  const auto min_support = static_cast<std::size_t>(std::ceil(s.min_share * static_cast<double>(pts.size())));
  std::mt19937 rng(7);  // fixed: the same cloud gives the same floor
  const auto first = largestPlane(pts, up, std::cos(s.max_tilt_deg * M_PI / 180.0), min_support, s, rng);
  if (!first) return std::nullopt;
  FloorPlane floor = refine(pts, *first, s.inlier_m, up);
  // The largest level plane may be a table or a bed: the floor is the lowest of the planes parallel to it
  // that hold enough points.
  constexpr double kParallelCos = 0.996;  // within 5 degrees
  for (int level = 0; level < 4; ++level) {
    std::vector<Eigen::Vector3d> below;
    for (const auto& p : pts)
      if (floor.normal.dot(p) < floor.height - 3 * s.inlier_m) below.push_back(p);
    if (below.size() < min_support) break;
    const auto lower = largestPlane(below, floor.normal, kParallelCos, min_support, s, rng);
    if (!lower) break;
    floor = refine(pts, *lower, s.inlier_m, up);
  }
  return floor;
}

GridSettings groundedGrid(const GridSettings& grid, const std::optional<FloorPlane>& floor) {
  GridSettings out = grid;
  out.axes_from = grid.up;
  double floor_height = grid.floor.height_m;
  if (floor && grid.floor.mode == FloorMode::kFit) {
    out.up = {floor->normal.x(), floor->normal.y(), floor->normal.z()};
    floor_height = floor->height;
  }
  out.height_min_m = floor_height + grid.height_min_m;
  out.height_max_m = floor_height + grid.height_max_m;
  return out;
}

}  // namespace bmp::mapper

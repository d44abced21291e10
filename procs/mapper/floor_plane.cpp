#include "mapper/floor_plane.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <unordered_map>
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

// Least-squares refits of a sample's plane on its support: each round takes in more of the surface.
constexpr int kRefineRounds = 3;

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

// The points of each cell of size cell_m, by index: a sample's three points are drawn from one cell.
class CellIndex {
 public:
  CellIndex(const std::vector<Eigen::Vector3d>& pts, double cell_m) {
    keys_.reserve(pts.size());
    for (std::size_t i = 0; i < pts.size(); ++i) {
      keys_.push_back(key(pts[i], cell_m));
      cells_[keys_.back()].push_back(i);
    }
  }
  const std::vector<std::size_t>& cellOf(std::size_t i) const { return cells_.at(keys_[i]); }

 private:
  // 21 bits a coordinate: +-1e6 cells, beyond any map's radius at any cell size allowed.
  static uint64_t key(const Eigen::Vector3d& p, double cell_m) {
    uint64_t k = 0;
    for (int a = 0; a < 3; ++a) {
      const double c = std::clamp(std::floor(p[a] / cell_m), -1048576.0, 1048575.0);
      k = (k << 21) | (static_cast<uint64_t>(static_cast<int64_t>(c) + 1048576) & 0x1FFFFF);
    }
    return k;
  }
  std::vector<uint64_t> keys_;
  std::unordered_map<uint64_t, std::vector<std::size_t>> cells_;
};

// The plane within acos(min_cos) of `up` that most of pts support (at least min_support), by RANSAC. The
// three points of a sample are neighbours (one cell): three points drawn from the whole cloud lie on one
// surface too rarely when the floor holds a sixth of it (0.5 % of samples), and 400 samples found a plane
// through clutter, tilted 13 degrees from Bonn's floor. Each sample's plane then takes the least-squares
// fit of its support, which the few points of a cell only approximate.
std::optional<FloorPlane> largestPlane(const std::vector<Eigen::Vector3d>& pts, const Eigen::Vector3d& up,
                                       double min_cos, std::size_t min_support, const FloorSettings& s,
                                       std::mt19937& rng) {
  if (pts.size() < 3) return std::nullopt;
  const CellIndex cells(pts, s.sample_cell_m);
  std::uniform_int_distribution<std::size_t> pick(0, pts.size() - 1);
  const auto support = [&](const FloorPlane& plane) {
    std::size_t n = 0;
    for (const auto& p : pts) n += std::abs(plane.normal.dot(p) - plane.height) < s.inlier_m;
    return n;
  };
  std::optional<FloorPlane> best;
  std::size_t best_support = 0;
  for (int it = 0; it < s.iterations; ++it) {
    const std::size_t ia = pick(rng);
    const std::vector<std::size_t>& cell = cells.cellOf(ia);
    std::uniform_int_distribution<std::size_t> near(0, cell.size() - 1);
    const Eigen::Vector3d& a = pts[ia];
    const Eigen::Vector3d n = (pts[cell[near(rng)]] - a).cross(pts[cell[near(rng)]] - a);
    if (n.norm() < 1e-9) continue;
    FloorPlane plane;
    plane.normal = n.normalized();
    if (plane.normal.dot(up) < 0) plane.normal = -plane.normal;
    if (plane.normal.dot(up) < min_cos) continue;
    plane.height = plane.normal.dot(a);
    std::size_t count = support(plane);
    if (count < min_support || count <= best_support) continue;
    for (int round = 0; round < kRefineRounds; ++round) {
      const FloorPlane refined = refine(pts, plane, s.inlier_m, up);
      const std::size_t refined_count = support(refined);
      if (refined.normal.dot(up) < min_cos || refined_count < count) break;
      plane = refined;
      count = refined_count;
    }
    best = plane;
    best_support = count;
  }
  return best;
}

// The plane's direction polished on grids of directions around its normal, coarse then fine: the one whose
// heights put the most points within a 2 x inlier_m window near the plane's height. A sample refined by
// least squares stops where its band of support stops growing, which can leave it a degree or two off the
// floor: 9 cm at 4 m, most of the 10 cm under the grid's band.
constexpr double kPolishDeg[] = {3.0, 1.0};       // each grid's reach either way ...
constexpr double kPolishStepDeg[] = {1.0, 0.25};  // ... and step
constexpr double kPolishReachM = 0.15;            // the window's centre within this of the plane's height
FloorPlane polish(const std::vector<Eigen::Vector3d>& pts, const FloorPlane& plane, double inlier_m) {
  const double bin = inlier_m / 2.0;
  const int bins = static_cast<int>(std::ceil(2.0 * kPolishReachM / bin)) + 4;
  std::vector<int> histogram(static_cast<std::size_t>(bins));
  FloorPlane best = plane;
  for (int level = 0; level < 2; ++level) {
    const FloorPlane centre = best;
    const Eigen::Vector3d e1 = centre.normal.unitOrthogonal();
    const Eigen::Vector3d e2 = centre.normal.cross(e1);
    const double lowest = centre.height - kPolishReachM - 2.0 * bin;
    const int steps = static_cast<int>(std::lround(kPolishDeg[level] / kPolishStepDeg[level]));
    const double step = kPolishStepDeg[level] * M_PI / 180.0;
    int best_count = -1;
    for (int i = -steps; i <= steps; ++i)
      for (int j = -steps; j <= steps; ++j) {
        const Eigen::Vector3d n =
            (centre.normal + std::tan(i * step) * e1 + std::tan(j * step) * e2).normalized();
        std::fill(histogram.begin(), histogram.end(), 0);
        for (const auto& p : pts) {
          const double k = std::floor((n.dot(p) - lowest) / bin);
          if (k >= 0 && k < bins) ++histogram[static_cast<std::size_t>(k)];
        }
        for (int k = 0; k + 4 <= bins; ++k) {
          const int count = histogram[k] + histogram[k + 1] + histogram[k + 2] + histogram[k + 3];
          if (count > best_count) {
            best_count = count;
            best.normal = n;
            best.height = lowest + (k + 2) * bin;
          }
        }
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
  FloorPlane floor = refine(pts, polish(pts, *first, s.inlier_m), s.inlier_m, up);
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
    floor = refine(pts, polish(pts, *lower, s.inlier_m), s.inlier_m, up);
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

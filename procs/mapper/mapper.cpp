#include "mapper/mapper.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <unordered_map>
#include <unordered_set>

#include "mapper/keyframe_cloud.hpp"
#include "mapper/voxel_filter.hpp"

namespace bmp::mapper {

namespace {

// Appended points wait unfiltered until they outnumber this share of the filtered ones (or someone asks for
// the cloud): re-filtering the whole map for every keyframe would cost O(map) per keyframe.
constexpr double kRefilterShare = 0.5;
constexpr std::size_t kRefilterMinimum = 200000;

std::vector<Eigen::Vector3f> positions(const PointList& points) {
  std::vector<Eigen::Vector3f> out;
  out.reserve(points.size());
  for (const auto& p : points) out.push_back(p.position());
  return out;
}

// The voxel of p at `leaf` metres as one key (21 bits per axis: +-52 km at 5 cm).
uint64_t voxelKey(const Eigen::Vector3f& p, float leaf) {
  const auto axis = [leaf](float v) {
    return static_cast<uint64_t>(static_cast<int64_t>(std::floor(v / leaf)) + (int64_t{1} << 20)) & 0x1FFFFFu;
  };
  return axis(p.x()) | axis(p.y()) << 21 | axis(p.z()) << 42;
}

ColoredPoint transformed(const SE3& T, const ColoredPoint& p) {
  const Eigen::Vector3d q = T * Eigen::Vector3d(p.x, p.y, p.z);
  return ColoredPoint{
      static_cast<float>(q.x()), static_cast<float>(q.y()), static_cast<float>(q.z()), p.r, p.g, p.b};
}

}  // namespace

Mapper::Mapper(const MapperSettings& settings) : settings_(settings), octree_(settings_.octomap) {}
Mapper::~Mapper() = default;

IntegrateResult Mapper::integrate(const KeyframeInput& kf) {
  ++map_revision_;
  Stopwatch watch;
  IntegrateResult result;
  result.reason = refusalOfFirst(kf);
  if (result.reason.empty() && hasKeyframe(kf.id))
    result.reason = "a keyframe with this id was already mapped";
  if (!result.reason.empty()) return result;
  const int64_t revisited = revisitOf(kf.T_world_cam);
  if (revisited < 0 && keyframes_.size() >= static_cast<std::size_t>(settings_.max_keyframes)) {
    result.reason = "the map holds max_keyframes (" + std::to_string(settings_.max_keyframes) +
                    ") keyframes; only revisits of them are taken";
    return result;
  }

  if (!rays_.fits(kf.camera)) rays_ = RayTable(kf.camera);
  Stored stored;
  stored.arrival = arrivals_++;
  stored.T_world_cam = kf.T_world_cam;
  stored.local = voxelFilter(backProject(kf, rays_, settings_.cloud), settings_.cloud.keyframe_voxel_m);
  // Down-sampled to the octree's leaves before ray casting, so integration keeps up.
  stored.octree_local = positions(voxelFilter(stored.local, settings_.octomap.resolution_m));
  insertIntoOctree(stored);
  result.points = stored.local.size();
  output_stale_ = true;
  appendToCloud(stored);
  if (revisited >= 0) {
    mergeInto(keyframes_.at(revisited), stored);
    merged_.emplace(kf.id, revisited);
  } else {
    keyframes_.emplace(kf.id, std::move(stored));
  }
  result.ok = true;
  result.milliseconds = watch.elapsedMs();
  integration_ms_.add(result.milliseconds);
  return result;
}

PoseUpdateResult Mapper::updatePoses(const std::vector<PoseUpdate>& updates) {
  ++map_revision_;
  PoseUpdateResult result;
  for (const auto& u : updates) {
    const auto it = keyframes_.find(u.id);
    // A merged revisit keeps nothing of its own to move: its points follow the keyframe it was merged into.
    const std::string pose_problem = checkPose(u.T_world_cam);
    const std::string problem = pose_problem.empty() ? checkPlace(u.T_world_cam) : pose_problem;
    if (it == keyframes_.end() && merged_.count(u.id) != 0 && problem.empty()) {
      ++result.applied;
      result.applied_ids.push_back(u.id);
      continue;
    }
    const std::string why = it == keyframes_.end() ? "unknown keyframe" : problem;
    if (!why.empty()) {
      result.rejected.push_back("keyframe " + std::to_string(u.id) + ": " + why);
      continue;
    }
    it->second.T_world_cam = u.T_world_cam;
    cloud_stale_ = output_stale_ = true;
    octree_stale_ = octree_stale_ || movedBeyondThresholds(it->second);
    ++result.applied;
    result.applied_ids.push_back(u.id);
  }
  return result;
}

std::string Mapper::refusalOfFirst(const KeyframeInput& kf) const {
  std::string why = checkKeyframe(kf);
  return why.empty() ? checkPlace(kf.T_world_cam) : why;
}

std::string Mapper::checkPlace(const SE3& T_world_cam) const {
  const double distance = T_world_cam.translation().norm();
  if (distance <= settings_.world_radius_m) return "";
  return "pose " + std::to_string(static_cast<int64_t>(distance)) +
         " m from the world origin, beyond world_radius_m " +
         std::to_string(static_cast<int64_t>(settings_.world_radius_m));
}

bool Mapper::movedBeyondThresholds(const Stored& kf) const {
  const SE3 delta = kf.T_world_cam_in_octree.inverse() * kf.T_world_cam;
  return delta.translation().norm() > settings_.rebuild.min_translation_m ||
         rotationAngle(delta) * 180.0 / M_PI > settings_.rebuild.min_rotation_deg;
}

void Mapper::mergeInto(Stored& into, const Stored& revisit) const {
  // The revisit's points in the stored keyframe's camera frame, then both voxel-filtered again: what the
  // revisit saw anew (space a person hid before) is kept, what it saw again adds nothing, so a keyframe's
  // cloud is bounded by the voxels of its view.
  const SE3 T_into_revisit = into.T_world_cam.inverse() * revisit.T_world_cam;
  PointList local = into.local;
  for (const auto& p : revisit.local) local.push_back(transformed(T_into_revisit, p));
  into.local = voxelFilter(local, settings_.cloud.keyframe_voxel_m);
  // Its rays to where the keyframe's own rays end add nothing a rebuild needs (the same rays, within the
  // merge distance: a neighbouring voxel counts, as the same surface seen from up to 5 cm away may fall into
  // it); those to new endpoints are what clears a ghost, so they are kept as a scan of their own.
  const auto leaf = static_cast<float>(settings_.octomap.resolution_m);
  std::unordered_set<uint64_t> own;
  own.reserve(27 * into.octree_local.size());
  for (const auto& p : into.octree_local)
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) own.insert(voxelKey(p + leaf * Eigen::Vector3f(dx, dy, dz), leaf));
  const Eigen::Isometry3f T = T_into_revisit.cast<float>();
  Scan scan{T_into_revisit.translation().cast<float>(), {}, revisit.arrival};
  for (const auto& p : revisit.octree_local) {
    const Eigen::Vector3f q = T * p;
    if (own.count(voxelKey(q, leaf)) == 0) scan.points.push_back(q);
  }
  countSeenAgain(into, revisit, T);
  if (!scan.points.empty()) into.revisits.push_back(std::move(scan));
  if (into.revisits.size() <= static_cast<std::size_t>(settings_.merge.max_scans)) return;
  // The oldest kept scan's endpoints join the keyframe's own: its evidence against a ghost is old by now.
  PointList rays;
  rays.reserve(into.octree_local.size() + into.revisits.front().points.size());
  for (const auto& p : into.octree_local) rays.push_back(ColoredPoint{p.x(), p.y(), p.z(), 0, 0, 0});
  for (const auto& p : into.revisits.front().points)
    rays.push_back(ColoredPoint{p.x(), p.y(), p.z(), 0, 0, 0});
  std::unordered_map<uint64_t, uint8_t> counts;  // the endpoints' counts carry over, by voxel
  for (std::size_t i = 0; i < into.octree_local.size(); ++i)
    counts[voxelKey(into.octree_local[i], leaf)] = into.seen_again[i];
  into.octree_local = positions(voxelFilter(rays, settings_.octomap.resolution_m));
  into.seen_again.assign(into.octree_local.size(), 0);
  for (std::size_t i = 0; i < into.octree_local.size(); ++i) {
    const auto it = counts.find(voxelKey(into.octree_local[i], leaf));
    if (it != counts.end()) into.seen_again[i] = it->second;
  }
  into.revisits.erase(into.revisits.begin());
}

void Mapper::countSeenAgain(Stored& into, const Stored& revisit,
                            const Eigen::Isometry3f& T_into_revisit) const {
  const auto leaf = static_cast<float>(settings_.octomap.resolution_m);
  std::unordered_set<uint64_t> ends;
  ends.reserve(revisit.octree_local.size());
  for (const auto& p : revisit.octree_local) ends.insert(voxelKey(T_into_revisit * p, leaf));
  const int most = std::min(255, octree_.saturatingCasts());
  into.seen_again.resize(into.octree_local.size(), 0);
  for (std::size_t i = 0; i < into.octree_local.size(); ++i) {
    const Eigen::Vector3f& p = into.octree_local[i];
    bool seen = false;  // within a neighbouring voxel, as for the rays not kept
    for (int dx = -1; dx <= 1 && !seen; ++dx)
      for (int dy = -1; dy <= 1 && !seen; ++dy)
        for (int dz = -1; dz <= 1 && !seen; ++dz)
          seen = ends.count(voxelKey(p + leaf * Eigen::Vector3f(dx, dy, dz), leaf)) != 0;
    if (seen && into.seen_again[i] < most) ++into.seen_again[i];
    if (seen) into.again_arrival = revisit.arrival;  // cast again as the last of them came
  }
}

int64_t Mapper::revisitOf(const SE3& T) const {
  const MergeSettings& m = settings_.merge;
  if (m.max_translation_m <= 0 && m.max_rotation_deg <= 0) return -1;
  for (const auto& entry : keyframes_) {
    const SE3 delta = entry.second.T_world_cam.inverse() * T;
    if (delta.translation().norm() <= m.max_translation_m &&
        rotationAngle(delta) * 180.0 / M_PI <= m.max_rotation_deg)
      return entry.first;
  }
  return -1;
}

bool Mapper::maintain(double now_s) {
  if (rebuild_) return rebuild_->done() && finishRebuild();
  if (!octree_stale_ || now_s - last_rebuild_s_ < settings_.rebuild.min_interval_s) return false;
  last_rebuild_s_ = now_s;
  startRebuild();
  return false;
}

bool Mapper::finishRebuild() {
  if (!rebuild_) return false;
  // Released first: a rebuild that threw (out of memory) is reported by the caller, the octree stays stale
  // and the next maintain() starts another, instead of asking this one again and again.
  const std::unique_ptr<BackgroundRebuild> job = std::move(rebuild_);
  std::unique_ptr<OccupancyMap> octree = job->take();
  for (const auto& cast : cast_since_rebuild_) castInto(*octree, cast);
  rebuilt(std::move(*octree));
  return true;
}

void Mapper::flush() {
  finishRebuild();
  if (octree_stale_) {
    startRebuild();
    finishRebuild();
  }
  cloud();
}

std::vector<OctreeCast> Mapper::allCasts() const {
  // Every cast again in the order it first came (the clamped log-odds are not commutative: ten hits of a
  // mover then twenty misses of revisits leave free space, the misses first an obstacle).
  std::vector<std::pair<int64_t, OctreeCast>> casts;
  for (const auto& entry : keyframes_) {
    const Stored& kf = entry.second;
    const Eigen::Isometry3f T = kf.T_world_cam.cast<float>();
    casts.push_back({kf.arrival, OctreeCast{T, Eigen::Vector3f::Zero(), kf.octree_local, 1}});
    if (kf.again_arrival >= 0) {
      // The rays merged revisits cast again to the keyframe's endpoints, grouped by how many did.
      std::map<int, std::vector<Eigen::Vector3f>> again;
      for (std::size_t i = 0; i < kf.seen_again.size() && i < kf.octree_local.size(); ++i)
        if (kf.seen_again[i] > 0) again[kf.seen_again[i]].push_back(kf.octree_local[i]);
      for (auto& [times, points] : again)
        casts.push_back({kf.again_arrival, OctreeCast{T, Eigen::Vector3f::Zero(), std::move(points), times}});
    }
    for (const Scan& scan : kf.revisits)
      casts.push_back({scan.arrival, OctreeCast{T, scan.origin, scan.points, 1}});
  }
  std::stable_sort(casts.begin(), casts.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<OctreeCast> ordered;
  ordered.reserve(casts.size());
  for (auto& c : casts) ordered.push_back(std::move(c.second));
  return ordered;
}

void Mapper::startRebuild() {
  rebuild_watch_.restart();
  rebuild_poses_.clear();
  for (const auto& entry : keyframes_) rebuild_poses_.emplace(entry.first, entry.second.T_world_cam);
  cast_since_rebuild_.clear();
  rebuild_ = std::make_unique<BackgroundRebuild>(settings_.octomap, allCasts());
}

void Mapper::rebuilt(OccupancyMap&& octree) {
  octree_ = std::move(octree);
  cast_since_rebuild_.clear();
  for (const auto& [id, pose] : rebuild_poses_) keyframes_.at(id).T_world_cam_in_octree = pose;
  rebuild_poses_.clear();
  // Poses updated while it ran may have moved keyframes beyond the thresholds again.
  octree_stale_ = std::any_of(keyframes_.begin(), keyframes_.end(),
                              [this](const auto& entry) { return movedBeyondThresholds(entry.second); });
  output_stale_ = true;
  ++rebuilds_;
  last_rebuild_ms_ = rebuild_watch_.elapsedMs();
}

void Mapper::insertIntoOctree(Stored& kf) {
  OctreeCast cast{kf.T_world_cam.cast<float>(), Eigen::Vector3f::Zero(), kf.octree_local, 1};
  castInto(octree_, cast);
  if (rebuild_) cast_since_rebuild_.push_back(std::move(cast));
  kf.T_world_cam_in_octree = kf.T_world_cam;
}

void Mapper::appendToCloud(const Stored& kf) {
  for (const auto& p : kf.local) world_cloud_.push_back(transformed(kf.T_world_cam, p));
  const std::size_t waiting = world_cloud_.size() - filtered_size_;
  if (waiting > std::max(kRefilterMinimum, static_cast<std::size_t>(kRefilterShare * filtered_size_))) {
    world_cloud_ = voxelFilter(world_cloud_, settings_.cloud.map_voxel_m);
    filtered_size_ = world_cloud_.size();
  }
}

const PointList& Mapper::cloud() {
  // Carving is judged on the octree as it is (a pending rebuild after small pose updates changes little;
  // flush() rebuilds before files are written).
  const PointList& all = stitched();
  if (!output_stale_) return output_cloud_;
  output_stale_ = false;
  const double below = settings_.cloud.drop_carved_below;
  if (below <= 0) return output_cloud_ = all;
  output_cloud_.clear();
  output_cloud_.reserve(all.size());
  for (const auto& p : all) {
    // -1 (unknown) keeps the point: a leaf never seen through has no evidence against it.
    const double probability = octree_.probability(p.position().cast<double>());
    if (probability < 0 || probability >= below) output_cloud_.push_back(p);
  }
  return output_cloud_;
}

const std::optional<FloorPlane>& Mapper::floor() {
  if (settings_.grid.floor.mode == FloorMode::kFit && floor_revision_ != map_revision_) {
    const auto& up = settings_.grid.up;
    // A floor once found stays until a refit finds one again: near the support threshold the fit can miss
    // it for a keyframe or two, and the grid would jump between two frames (seen on the synthetic default).
    if (auto fitted = fitFloor(stitched(), Eigen::Vector3d(up[0], up[1], up[2]), settings_.grid.floor))
      floor_ = fitted;
    floor_revision_ = map_revision_;
  }
  return floor_;
}

OccupancyGrid2D Mapper::grid() {
  std::vector<Eigen::Vector3d> centres;
  centres.reserve(keyframes_.size());
  // Only keyframes that saw something stand on the floor: one with no depth (another publisher's, far away)
  // would widen the grid to reach it.
  for (const auto& entry : keyframes_)
    if (!entry.second.local.empty()) centres.push_back(entry.second.T_world_cam.translation());
  return octree_.project(groundedGrid(), centres);
}

GridSettings Mapper::groundedGrid() {
  return bmp::mapper::groundedGrid(settings_.grid, floor());
}

const PointList& Mapper::stitched() {
  if (cloud_stale_) {
    world_cloud_.clear();
    for (const auto& entry : keyframes_)
      for (const auto& p : entry.second.local)
        world_cloud_.push_back(transformed(entry.second.T_world_cam, p));
    filtered_size_ = 0;
    cloud_stale_ = false;
  }
  if (filtered_size_ != world_cloud_.size()) {
    world_cloud_ = voxelFilter(world_cloud_, settings_.cloud.map_voxel_m);
    filtered_size_ = world_cloud_.size();
  }
  return world_cloud_;
}

PointList Mapper::viewerCloud() {
  return voxelFilter(cloud(), settings_.cloud.viewer_voxel_m);
}

}  // namespace bmp::mapper

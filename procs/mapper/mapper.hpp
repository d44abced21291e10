#pragma once
// bmp::mapper::Mapper, the one entry point of the dense static map: keyframes in (integrate), pose updates
// after bundle adjustment in (updatePoses), and out the stitched coloured cloud, the OctoMap and the 2-D
// grid. Read integrate() first: back-project the static pixels, voxel-filter, place in the world, stitch,
// insert into the octree by ray casting.
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "bmp/common/se3.hpp"
#include "bmp/common/timing.hpp"
#include "mapper/floor_plane.hpp"
#include "mapper/keyframe_input.hpp"
#include "mapper/mapper_settings.hpp"
#include "mapper/occupancy_grid.hpp"
#include "mapper/occupancy_map.hpp"
#include "mapper/octree_rebuild.hpp"
#include "mapper/point_types.hpp"
#include "mapper/ray_table.hpp"

namespace bmp::mapper {

struct IntegrateResult {
  bool ok = false;
  std::string reason;       // why the keyframe was refused ("" when ok)
  std::size_t points = 0;   // in its filtered local cloud
  double milliseconds = 0;  // integration time
};

struct PoseUpdate {
  int64_t id = 0;
  SE3 T_world_cam = SE3::Identity();
};

struct PoseUpdateResult {
  int applied = 0;
  std::vector<int64_t> applied_ids;   // the keyframes (or merged revisits) whose update was applied
  std::vector<std::string> rejected;  // one line per refused update, naming the keyframe id and the reason
};

class Mapper {
 public:
  explicit Mapper(const MapperSettings& settings);
  ~Mapper();
  Mapper(const Mapper&) = delete;
  Mapper& operator=(const Mapper&) = delete;

  // Maps one keyframe, or refuses it (reason in the result; nothing else changes): a keyframe that fails
  // checkKeyframe, or whose id was seen before.
  IntegrateResult integrate(const KeyframeInput& kf);
  // Why a map of no keyframes yet would refuse kf (checkKeyframe, or a pose beyond world_radius_m), or "":
  // asked before this map is dropped for another camera's.
  std::string refusalOfFirst(const KeyframeInput& kf) const;
  // New poses of known keyframes: the cloud follows at once (on the next cloud()), the octree at the next
  // maintain() that is due. Updates for unknown ids or with invalid poses are refused one by one.
  PoseUpdateResult updatePoses(const std::vector<PoseUpdate>& updates);
  // Starts rebuilding the octree from the stored keyframe clouds, on a thread of its own, when some keyframe
  // moved beyond the rebuild thresholds since its rays were cast and the last rebuild started
  // min_interval_s ago; or swaps in a finished rebuild. now_s: a monotonic clock in seconds. Returns true
  // when it swapped one in. Until then the octree is the one before, with every keyframe integrated since
  // cast into it; after, it is the rebuilt one with those keyframes cast again on top, in the order they
  // came: the octree a rebuild at its start, in this thread, would have led to.
  bool maintain(double now_s);
  // Waits for a running rebuild and swaps it in; true when there was one.
  bool finishRebuild();
  bool rebuilding() const { return rebuild_ != nullptr; }
  // Everything up to date whatever the interval (before files are written at exit).
  void flush();

  // The stitched cloud, world frame, voxel-filtered at map_voxel_m, without the points whose octree leaf
  // was carved below cloud.drop_carved_below (the octree brought up to date first).
  const PointList& cloud();
  // The cloud down-sampled to viewer_voxel_m.
  PointList viewerCloud();
  // The grid on the floor (fitted again when keyframes came or moved since the last fit).
  // Unknown cells around each kept keyframe's camera are free (grid.camera_free_radius_m).
  OccupancyGrid2D grid();
  // settings.grid with up and the height band in the world, measured from the floor.
  GridSettings groundedGrid();
  // The fitted floor, or nullopt (none found yet, or floor.mode fixed).
  const std::optional<FloorPlane>& floor();
  const OccupancyMap& occupancy() const { return octree_; }

  // Points in the stitched cloud, some perhaps still waiting for the voxel filter (for status lines).
  std::size_t pointCount() const { return world_cloud_.size(); }
  // Keyframes whose cloud is kept, and those merged into one of them (merge settings: a revisit).
  std::size_t keyframeCount() const { return keyframes_.size(); }
  std::size_t mergedCount() const { return merged_.size(); }
  bool hasKeyframe(int64_t id) const { return keyframes_.count(id) != 0 || merged_.count(id) != 0; }
  const MapperSettings& settings() const { return settings_; }
  const TimingStats& integrationTimes() const { return integration_ms_; }
  int rebuildCount() const { return rebuilds_; }
  double lastRebuildMs() const { return last_rebuild_ms_; }  // from its start to its swap
  bool octreeStale() const { return octree_stale_; }

 private:
  // A revisit's rays, in the stored keyframe's camera frame: where it was, and the endpoints it found where
  // the keyframe's own rays did not end (space a person hid then, seen now).
  struct Scan {
    Eigen::Vector3f origin = Eigen::Vector3f::Zero();
    std::vector<Eigen::Vector3f> points;
    int64_t arrival = 0;  // when its revisit came (Mapper::arrivals_)
  };
  struct Stored {
    SE3 T_world_cam = SE3::Identity();            // the newest pose
    SE3 T_world_cam_in_octree = SE3::Identity();  // the pose its rays were cast from
    PointList local;                              // camera frame, keyframe_voxel_m
    std::vector<Eigen::Vector3f> octree_local;    // camera frame, down-sampled to the octree's resolution
    std::vector<Scan> revisits;                   // the newest merged revisits' rays, oldest first
    // Per endpoint of octree_local: how many merged revisits had a ray ending there too. Those rays are not
    // kept, but each cleared what it passed through, so a rebuild casts the keyframe's ray to the endpoint
    // that many times more (up to the octree's saturatingCasts: its clamping forgets beyond that).
    std::vector<uint8_t> seen_again;
    int64_t arrival = 0;         // when it came, counted over every keyframe integrated (Mapper::arrivals_)
    int64_t again_arrival = -1;  // when the last revisit that saw its endpoints again came (-1: none)
  };
  void appendToCloud(const Stored& kf);
  void insertIntoOctree(Stored& kf);
  // Every cast the octree holds, in the order they came, at the keyframes' newest poses.
  std::vector<OctreeCast> allCasts() const;
  void startRebuild();
  // The octree rebuilt: the keyframes' rays were cast from the poses they had when it started.
  void rebuilt(OccupancyMap&& octree);
  const PointList& stitched();
  bool movedBeyondThresholds(const Stored& kf) const;
  // Why a finite pose is outside the mapped world (settings_.world_radius_m), or "".
  std::string checkPlace(const SE3& T_world_cam) const;
  // Folds a revisit's cloud into a stored keyframe's (its camera frame), voxel-filtered again, and keeps its
  // rays as a scan of their own (up to merge.max_scans; older ones folded into the keyframe's own).
  void mergeInto(Stored& into, const Stored& revisit) const;
  // Counts, per endpoint of into's own rays, a revisit's ray ending there too (Stored::seen_again).
  void countSeenAgain(Stored& into, const Stored& revisit, const Eigen::Isometry3f& T_into_revisit) const;
  // The id of a stored keyframe whose pose is within the merge thresholds of T, or -1.
  int64_t revisitOf(const SE3& T_world_cam) const;

  MapperSettings settings_;
  RayTable rays_;
  std::map<int64_t, Stored> keyframes_;  // by id: rebuilds replay them in creation order
  std::map<int64_t, int64_t> merged_;    // a revisit's id -> the stored keyframe it was merged into
  PointList world_cloud_;
  std::size_t filtered_size_ = 0;  // world_cloud_'s first part that is already voxel-filtered
  bool cloud_stale_ = false;       // a pose changed: rebuild the cloud from the local clouds
  PointList output_cloud_;         // world_cloud_ without carved points: what cloud() returns
  bool output_stale_ = true;       // the cloud or the octree changed since output_cloud_ was made
  OccupancyMap octree_;
  bool octree_stale_ = false;
  double last_rebuild_s_ = -1e300;
  int rebuilds_ = 0;
  double last_rebuild_ms_ = 0;
  // The running rebuild, the poses it casts from, and what was cast into octree_ since it started (cast
  // again into the rebuilt octree before the swap).
  std::unique_ptr<BackgroundRebuild> rebuild_;
  std::map<int64_t, SE3> rebuild_poses_;
  std::vector<OctreeCast> cast_since_rebuild_;
  Stopwatch rebuild_watch_;
  int64_t arrivals_ = 0;  // keyframes integrated so far, kept or merged: the order of their casts
  TimingStats integration_ms_;
  std::optional<FloorPlane> floor_;
  int64_t floor_revision_ = -1;  // map_revision_ when floor_ was fitted
  int64_t map_revision_ = 0;     // counts integrations and pose updates
};

}  // namespace bmp::mapper

// The octree and the grid from hand-made keyframes: free space carved, a ghost cleared once the space behind
// it is seen again, the grid's floor plane, and pose updates moving the cloud, the octree and the grid.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <memory>
#include <thread>

#include "mapper/map_pictures.hpp"
#include "mapper/mapper.hpp"
#include "mapper_test_util.hpp"

namespace bmp::mapper {
namespace {

using test::translation;
using test::wallKeyframe;

// Depths a little off voxel edges (multiples of 0.05), so a point's voxel does not depend on rounding.
constexpr double kWall = 3.02;
constexpr double kNear = 1.52;

int8_t gridAt(const OccupancyGrid2D& grid, const Eigen::Vector3d& p_world) {
  int col = 0, row = 0;
  if (!grid.cellOf(grid.frame.planar(p_world), col, row)) return kCellUnknown;
  return grid.at(col, row);
}

Eigen::Vector3d cloudMean(const PointList& cloud) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const auto& p : cloud) sum += p.position().cast<double>();
  return sum / static_cast<double>(cloud.size());
}

TEST(OccupancyMap, WallOccupiedSpaceBeforeItFreeBehindItUnknown) {
  Mapper mapper(test::testSettings());
  ASSERT_TRUE(mapper.integrate(wallKeyframe(0, SE3::Identity(), kWall)).ok);
  const OccupancyMap& map = mapper.occupancy();
  EXPECT_EQ(map.query({0, 0, kWall + 0.005}), Occupancy::kOccupied);
  EXPECT_EQ(map.query({0.5, -0.3, 1.5}), Occupancy::kFree);
  EXPECT_EQ(map.query({0, 0, 4.0}), Occupancy::kUnknown);
  EXPECT_GT(map.nodeCount(), 100u);
}

// With the default settings every point the cloud keeps is a hit in the octree: a wall just inside
// cloud.max_depth_m is occupied at the image's corner too, where its ray is 1.26 times its depth long.
TEST(OccupancyMap, AKeptPointAtTheImagesCornerIsAHit) {
  Mapper mapper{MapperSettings{}};
  const double depth = 4.87;
  ASSERT_LT(depth, MapperSettings{}.cloud.max_depth_m);
  ASSERT_TRUE(mapper.integrate(wallKeyframe(0, SE3::Identity(), depth)).ok);
  const CameraIntrinsics k = test::smallCamera();
  const Eigen::Vector3d corner((2.0 - k.cx) / k.fx * depth, (2.0 - k.cy) / k.fy * depth, depth + 0.005);
  ASSERT_GT(corner.norm(), 6.0);
  EXPECT_EQ(mapper.occupancy().query(corner), Occupancy::kOccupied);
  EXPECT_EQ(mapper.occupancy().query({0, 0, depth + 0.005}), Occupancy::kOccupied);
}

TEST(OccupancyMap, GhostIsClearedWhenTheSpaceBehindItIsSeenAgain) {
  Mapper mapper(test::testSettings());
  // A mover, not masked, stands in front of the wall in the first keyframe only.
  ASSERT_TRUE(mapper.integrate(wallKeyframe(0, SE3::Identity(), kWall, cv::Rect(70, 50, 20, 20), kNear)).ok);
  const Eigen::Vector3d ghost(0, 0, kNear + 0.005);
  EXPECT_EQ(mapper.occupancy().query(ghost), Occupancy::kOccupied);
  // One hit outweighs two misses under OctoMap's default sensor model (0.85 against 2 x 0.41 log-odds) ...
  ASSERT_TRUE(mapper.integrate(wallKeyframe(1, SE3::Identity(), kWall)).ok);
  ASSERT_TRUE(mapper.integrate(wallKeyframe(2, SE3::Identity(), kWall)).ok);
  EXPECT_EQ(mapper.occupancy().query(ghost), Occupancy::kOccupied);
  // ... and a third clears it.
  ASSERT_TRUE(mapper.integrate(wallKeyframe(3, SE3::Identity(), kWall)).ok);
  EXPECT_EQ(mapper.occupancy().query(ghost), Occupancy::kFree);
  EXPECT_EQ(mapper.occupancy().query({0, 0, kWall + 0.005}), Occupancy::kOccupied);
}

std::size_t pointsNear(const PointList& cloud, double depth) {
  std::size_t n = 0;
  for (const auto& p : cloud) n += std::abs(p.z - depth) < 0.03;
  return n;
}

TEST(CarvedPoints, AGhostLeavesTheCloudOnceItsLeafIsSeenThroughOftenEnough) {
  MapperSettings settings = test::testSettings();
  Mapper mapper(settings);
  settings.cloud.drop_carved_below = 0.0;
  Mapper keep_all(settings);
  for (Mapper* m : {&mapper, &keep_all})
    ASSERT_TRUE(m->integrate(wallKeyframe(0, SE3::Identity(), kWall, cv::Rect(70, 50, 20, 20), kNear)).ok);
  const std::size_t ghost_points = pointsNear(mapper.cloud(), kNear);
  ASSERT_GT(ghost_points, 10u);
  // Log-odds after one hit and n misses: 0.85 - 0.41 n. Free after 3 misses (p 0.41) but not yet below
  // drop_carved_below 0.2: a leaf seen through a few times keeps its points ...
  for (int id = 1; id <= 3; ++id) ASSERT_TRUE(mapper.integrate(wallKeyframe(id, SE3::Identity(), kWall)).ok);
  EXPECT_EQ(mapper.occupancy().query({0, 0, kNear + 0.005}), Occupancy::kFree);
  EXPECT_EQ(pointsNear(mapper.cloud(), kNear), ghost_points);
  // ... and after 6 misses (p 0.17) they are gone, while the wall stays whole.
  for (int id = 4; id <= 6; ++id) ASSERT_TRUE(mapper.integrate(wallKeyframe(id, SE3::Identity(), kWall)).ok);
  EXPECT_EQ(pointsNear(mapper.cloud(), kNear), 0u);
  EXPECT_GT(pointsNear(mapper.cloud(), kWall), 1000u);
  // drop_carved_below 0 keeps every point.
  for (int id = 1; id <= 6; ++id)
    ASSERT_TRUE(keep_all.integrate(wallKeyframe(id, SE3::Identity(), kWall)).ok);
  EXPECT_EQ(pointsNear(keep_all.cloud(), kNear), ghost_points);
}

TEST(Revisits, AKeyframeNearAStoredOneIsFoldedIntoIt) {
  Mapper mapper(test::testSettings());
  ASSERT_TRUE(mapper.integrate(wallKeyframe(0, SE3::Identity(), kWall)).ok);
  const std::size_t points = mapper.cloud().size();
  // The same wall seen from 3 cm to the side (a hand-made wall keyframe's wall is at its own depth, so a
  // turned view would see another wall: turning is checked below).
  const SE3 near = translation(0.03, 0, 0);
  ASSERT_TRUE(mapper.integrate(wallKeyframe(1, near, kWall)).ok);
  EXPECT_EQ(mapper.keyframeCount(), 1u);
  EXPECT_EQ(mapper.mergedCount(), 1u);
  EXPECT_TRUE(mapper.hasKeyframe(1));
  EXPECT_FALSE(mapper.integrate(wallKeyframe(1, near, kWall)).ok);  // its id is taken
  // Surface seen again is not doubled (a 3 cm strip is new, and voxel centroids shift a little) ...
  EXPECT_LT(mapper.cloud().size(), points * 5 / 4);
  // ... and what only the revisit saw is kept: a wall 0.5 m further where the stored view had a mover.
  ASSERT_TRUE(
      mapper.integrate(wallKeyframe(3, SE3::Identity(), kWall, cv::Rect(0, 0, 20, 120), kWall + 0.5)).ok);
  EXPECT_EQ(mapper.mergedCount(), 2u);
  std::size_t behind = 0;
  for (const auto& p : mapper.cloud()) behind += std::abs(p.z - (kWall + 0.5)) < 0.03;
  EXPECT_GT(behind, 100u);
  // A pose update for the merged keyframe is accepted (its points are the stored keyframe's).
  EXPECT_EQ(mapper.updatePoses({{1, near}}).applied, 1);
  // 20 cm away, or turned by 10 degrees, is a new view: its cloud is kept.
  ASSERT_TRUE(mapper.integrate(wallKeyframe(2, translation(0.2, 0, 0), kWall)).ok);
  EXPECT_EQ(mapper.keyframeCount(), 2u);
  SE3 turned = SE3::Identity();
  turned.linear() = Eigen::AngleAxisd(10.0 * M_PI / 180.0, Eigen::Vector3d::UnitY()).toRotationMatrix();
  ASSERT_TRUE(mapper.integrate(wallKeyframe(4, turned, kWall)).ok);
  EXPECT_EQ(mapper.keyframeCount(), 3u);
  // Merging off (0, 0): every keyframe's cloud is kept.
  MapperSettings keep = test::testSettings();
  keep.merge = {0.0, 0.0};
  Mapper all(keep);
  ASSERT_TRUE(all.integrate(wallKeyframe(0, SE3::Identity(), kWall)).ok);
  ASSERT_TRUE(all.integrate(wallKeyframe(1, SE3::Identity(), kWall)).ok);
  EXPECT_EQ(all.keyframeCount(), 2u);
}

TEST(Revisits, MergedRaysStillClearAGhost) {
  Mapper mapper(test::testSettings());
  ASSERT_TRUE(mapper.integrate(wallKeyframe(0, SE3::Identity(), kWall, cv::Rect(70, 50, 20, 20), kNear)).ok);
  for (int id = 1; id <= 6; ++id) ASSERT_TRUE(mapper.integrate(wallKeyframe(id, SE3::Identity(), kWall)).ok);
  EXPECT_EQ(mapper.mergedCount(), 6u);
  const Eigen::Vector3d ghost(0, 0, kNear + 0.005);
  EXPECT_EQ(mapper.occupancy().query(ghost), Occupancy::kFree);
  // A rebuild (a pose update beyond the thresholds; flush() before files are written) casts each kept
  // revisit as the scan it was: the ghost stays cleared. Folded into one scan with the keyframe's own rays,
  // its cell was hit and passed through in that one scan, counted as hit, and the ghost came back.
  ASSERT_EQ(mapper.updatePoses({{0, translation(0.03, 0, 0)}}).applied, 1);
  mapper.flush();
  EXPECT_EQ(mapper.rebuildCount(), 1);
  EXPECT_EQ(mapper.occupancy().query(ghost + Eigen::Vector3d(0.03, 0, 0)), Occupancy::kFree);
  EXPECT_EQ(mapper.occupancy().query({0.03, 0, kWall + 0.005}), Occupancy::kOccupied);
}

// A ghost another keyframe put there (a mover seen from ten places nearby), cleared by twenty revisits of
// keyframe 0 that see the wall through it, stays cleared after a rebuild. Their rays end where keyframe
// 0's own end, so they are not kept as scans; a rebuild cast keyframe 0's rays once against the ten hits,
// and the ghost came back into the saved map (found by review).
TEST(Revisits, ARebuildKeepsAGhostClearedByRevisitsThatSawNothingNew) {
  Mapper mapper(test::testSettings());
  ASSERT_TRUE(mapper.integrate(wallKeyframe(0, SE3::Identity(), kWall)).ok);
  for (int id = 1; id <= 10; ++id)
    ASSERT_TRUE(mapper.integrate(wallKeyframe(id, translation(0.2 + 0.06 * id, 0, 0), kNear)).ok);
  const Eigen::Vector3d ghost(0.3, 0.0, kNear + 0.005);
  ASSERT_EQ(mapper.occupancy().query(ghost), Occupancy::kOccupied);
  for (int id = 11; id <= 30; ++id)
    ASSERT_TRUE(mapper.integrate(wallKeyframe(id, SE3::Identity(), kWall)).ok);
  EXPECT_EQ(mapper.mergedCount(), 20u);
  ASSERT_EQ(mapper.occupancy().query(ghost), Occupancy::kFree);
  // A pose update beyond the thresholds and back: the same poses, the octree rebuilt from the keyframes.
  ASSERT_EQ(mapper.updatePoses({{5, translation(0.53, 0, 0)}}).applied, 1);
  ASSERT_EQ(mapper.updatePoses({{5, translation(0.5, 0, 0)}}).applied, 1);
  mapper.flush();
  EXPECT_EQ(mapper.rebuildCount(), 1);
  EXPECT_EQ(mapper.occupancy().query(ghost), Occupancy::kFree);
  EXPECT_EQ(mapper.occupancy().query({0.0, 0.0, kWall + 0.005}), Occupancy::kOccupied);
}

TEST(PlaneFrame, AxesFollowTheConfiguredUp) {
  const PlaneFrame z_up = PlaneFrame::fromUp({0, 0, 1});
  EXPECT_TRUE(z_up.x_axis.isApprox(Eigen::Vector3d::UnitX()));
  EXPECT_TRUE(z_up.y_axis.isApprox(Eigen::Vector3d::UnitY()));
  const PlaneFrame camera = PlaneFrame::fromUp({0, -1, 0});  // the tracker's first camera: y down
  EXPECT_TRUE(camera.x_axis.isApprox(Eigen::Vector3d::UnitX()));
  EXPECT_TRUE(camera.y_axis.isApprox(Eigen::Vector3d::UnitZ()));  // forward
  const PlaneFrame tilted = PlaneFrame::fromUp({0.2, -0.9, 0.3});
  EXPECT_NEAR(tilted.R_world_plane().determinant(), 1.0, 1e-9);
  EXPECT_TRUE((tilted.R_world_plane().transpose() * tilted.R_world_plane()).isIdentity(1e-9));
}

TEST(PlaneFrame, ARefittedFloorDoesNotTurnTheGrid) {
  // A first camera pitched and rolled alike: the floor's normal has two near-equal small components, and
  // two refits a degree apart swap which is the smaller. The axes follow the configured up, so the grid's x
  // stays (near) world x instead of jumping to world z.
  const std::array<double, 3> configured{0.0, -1.0, 0.0};
  const PlaneFrame a = PlaneFrame::fromUp({0.170, -0.970, 0.174}, configured);
  const PlaneFrame b = PlaneFrame::fromUp({0.174, -0.970, 0.170}, configured);
  EXPECT_GT(a.x_axis.dot(b.x_axis), std::cos(2.0 * M_PI / 180.0));
  EXPECT_GT(a.x_axis.dot(Eigen::Vector3d::UnitX()), 0.98);
  // Without the configured up each normal picks its own least component: the axes are 90 degrees apart.
  EXPECT_LT(std::abs(PlaneFrame::fromUp({0.170, -0.970, 0.174})
                         .x_axis.dot(PlaneFrame::fromUp({0.174, -0.970, 0.170}).x_axis)),
            0.1);
}

TEST(OccupancyGrid, WallInTheBandIsOccupiedTheFloorBeforeItFree) {
  Mapper mapper(test::testSettings());  // up -y, band [-1, 0.5] m around the camera's height
  ASSERT_TRUE(mapper.integrate(wallKeyframe(0, SE3::Identity(), kWall)).ok);
  const OccupancyGrid2D grid = mapper.grid();
  EXPECT_NEAR(grid.resolution, 0.05, 1e-12);
  EXPECT_EQ(gridAt(grid, {0, 0, kWall + 0.005}), kCellOccupied);
  EXPECT_EQ(gridAt(grid, {0, 0, 1.5}), kCellFree);
  EXPECT_EQ(gridAt(grid, {0, 0, 4.5}), kCellUnknown);
  // The origin pose maps plane coordinates into the world: cell (0, 0)'s corner.
  const Eigen::Vector3d corner = grid.T_world_origin() * Eigen::Vector3d::Zero();
  EXPECT_TRUE(grid.frame.planar(corner).isApprox(grid.origin));
  // Outside the height band nothing counts: a band above the wall's top leaves every cell unknown.
  GridSettings above = mapper.settings().grid;
  above.height_min_m = 2.0;
  above.height_max_m = 3.0;
  // One unknown cell: a 0x0 image (as written before) is no map map_server or bmp-plan can load.
  const OccupancyGrid2D nothing = mapper.occupancy().project(above);
  EXPECT_EQ(nothing.width, 1);
  EXPECT_EQ(nothing.height, 1);
  EXPECT_EQ(nothing.cells, std::vector<int8_t>{kCellUnknown});
  // With nothing in the band, the floor where the camera stood is still free.
  above.camera_free_radius_m = 0.3;
  const OccupancyGrid2D discs = mapper.occupancy().project(above, {Eigen::Vector3d::Zero()});
  EXPECT_EQ(gridAt(discs, Eigen::Vector3d::Zero()), kCellFree);
}

// The column under a camera is never seen, so a planner refused to start where the robot stands. The floor
// around each keyframe's camera is free where nothing else is known, and never over an obstacle.
TEST(OccupancyGrid, TheFloorWhereTheCameraWasIsFree) {
  MapperSettings settings = test::testSettings();
  settings.grid.height_max_m = 0.5;  // the band ends 0.5 m below the camera: its rays reach it 1.1 m ahead
  Mapper mapper(settings);
  ASSERT_TRUE(mapper.integrate(wallKeyframe(0, SE3::Identity(), kWall)).ok);
  const OccupancyGrid2D grid = mapper.grid();
  EXPECT_EQ(gridAt(grid, {0, 0, 0}), kCellFree);
  EXPECT_EQ(gridAt(grid, {0.15, 0, 0}), kCellFree);
  EXPECT_EQ(gridAt(grid, {0, 0, 0.5}), kCellUnknown);  // beyond 0.2 m, still unseen
  EXPECT_EQ(gridAt(grid, {0, 0, 1.5}), kCellFree);
  EXPECT_EQ(gridAt(grid, {0, 0, kWall + 0.005}), kCellOccupied);
  // A camera centre at the wall leaves the wall occupied; radius 0 turns the rule off.
  const GridSettings grounded = mapper.groundedGrid();
  EXPECT_EQ(gridAt(mapper.occupancy().project(grounded, {{0, 0, kWall}}), {0, 0, kWall + 0.005}),
            kCellOccupied);
  GridSettings off = grounded;
  off.camera_free_radius_m = 0.0;
  EXPECT_EQ(gridAt(mapper.occupancy().project(off, {{0, 0, 0}}), {0, 0, 0}), kCellUnknown);
}

TEST(PoseUpdate, MovesTheCloudTheOctreeAndTheGrid) {
  Mapper mapper(test::testSettings());
  ASSERT_TRUE(mapper.integrate(wallKeyframe(7, SE3::Identity(), kWall)).ok);
  const Eigen::Vector3d before = cloudMean(mapper.cloud());
  const Eigen::Vector3d old_only(-1.5, 0, kWall + 0.005), new_only(2.5, 0, kWall + 0.005);
  EXPECT_EQ(mapper.occupancy().query(old_only), Occupancy::kOccupied);
  EXPECT_EQ(mapper.occupancy().query(new_only), Occupancy::kUnknown);

  const PoseUpdateResult r = mapper.updatePoses({{7, translation(1.0, 0, 0)}});
  EXPECT_EQ(r.applied, 1);
  EXPECT_TRUE(r.rejected.empty());
  EXPECT_TRUE(cloudMean(mapper.cloud()).isApprox(before + Eigen::Vector3d(1, 0, 0), 1e-3));
  EXPECT_TRUE(mapper.octreeStale());
  // The rebuild runs beside the mapper: until it is swapped in, the octree is the one before.
  EXPECT_FALSE(mapper.maintain(100.0));
  EXPECT_TRUE(mapper.rebuilding());
  EXPECT_EQ(mapper.occupancy().query(old_only), Occupancy::kOccupied);
  ASSERT_TRUE(mapper.finishRebuild());
  EXPECT_FALSE(mapper.rebuilding());
  EXPECT_EQ(mapper.occupancy().query(old_only), Occupancy::kUnknown);
  EXPECT_EQ(mapper.occupancy().query(new_only), Occupancy::kOccupied);
  const OccupancyGrid2D grid = mapper.grid();
  EXPECT_EQ(gridAt(grid, new_only), kCellOccupied);
  EXPECT_NE(gridAt(grid, old_only), kCellOccupied);
}

TEST(PoseUpdate, RebuildIsDebouncedAndSkipsTinyMoves) {
  Mapper mapper(test::testSettings());  // at most every 5 s; 2 cm or 1 degree
  ASSERT_TRUE(mapper.integrate(wallKeyframe(0, SE3::Identity(), kWall)).ok);
  mapper.updatePoses({{0, translation(0.005, 0, 0)}});
  EXPECT_FALSE(mapper.octreeStale());  // 5 mm: the octree stays, the cloud follows
  EXPECT_FALSE(mapper.maintain(0.0));
  EXPECT_FALSE(mapper.rebuilding());
  mapper.updatePoses({{0, translation(0.5, 0, 0)}});
  mapper.maintain(10.0);
  EXPECT_TRUE(mapper.rebuilding());
  // maintain() swaps it in once it is done (a loop, as the mapper's own), and only then.
  bool swapped = false;
  for (int turn = 0; turn < 60000 && !swapped; ++turn) {
    swapped = mapper.maintain(10.0);
    if (!swapped) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  ASSERT_TRUE(swapped);
  EXPECT_EQ(mapper.rebuildCount(), 1);
  mapper.updatePoses({{0, translation(1.0, 0, 0)}});
  EXPECT_FALSE(mapper.maintain(12.0));  // 2 s after the last rebuild started
  EXPECT_FALSE(mapper.rebuilding());
  EXPECT_TRUE(mapper.octreeStale());
  mapper.maintain(15.0);
  EXPECT_TRUE(mapper.finishRebuild());
  EXPECT_EQ(mapper.rebuildCount(), 2);
  mapper.updatePoses({{0, translation(2.0, 0, 0)}});
  mapper.flush();  // at exit: whatever the interval
  EXPECT_FALSE(mapper.octreeStale());
}

// A rebuild runs on its own thread while keyframes come (a rebuild in the mapper's thread took seconds at a
// few hundred keyframes, and the keyframes sent meanwhile were lost). Whenever it ends, the octree it leaves
// is the one a rebuild at its start in the mapper's thread leads to: the keyframes integrated meanwhile
// (a new one, and revisits merged into keyframes the rebuild casts) are cast again on top, in order.
TEST(PoseUpdate, ARebuildBesideIntegrationEndsAsOneAtItsStartWould) {
  const auto before = [](Mapper& m) {
    ASSERT_TRUE(m.integrate(wallKeyframe(0, SE3::Identity(), kWall, cv::Rect(70, 50, 20, 20), kNear)).ok);
    for (int id = 1; id <= 4; ++id)
      ASSERT_TRUE(m.integrate(wallKeyframe(id, translation(0.3 * id, 0, 0), kWall)).ok);
    ASSERT_EQ(m.updatePoses({{2, translation(0.65, 0, 0)}}).applied, 1);
  };
  const auto meanwhile = [](Mapper& m) {
    for (int id = 5; id <= 8; ++id) ASSERT_TRUE(m.integrate(wallKeyframe(id, SE3::Identity(), kWall)).ok);
    ASSERT_TRUE(m.integrate(wallKeyframe(9, translation(-0.4, 0, 0), kNear)).ok);
    ASSERT_EQ(m.updatePoses({{3, translation(0.95, 0, 0)}}).applied, 1);
  };
  Mapper beside(test::testSettings());
  before(beside);
  ASSERT_TRUE(beside.octreeStale());
  beside.maintain(100.0);
  ASSERT_TRUE(beside.rebuilding());
  meanwhile(beside);
  ASSERT_TRUE(beside.finishRebuild());
  EXPECT_EQ(beside.mergedCount(), 4u);

  Mapper inline_(test::testSettings());
  before(inline_);
  inline_.flush();  // rebuilt before it returns
  meanwhile(inline_);

  EXPECT_EQ(beside.rebuildCount(), 1);
  EXPECT_EQ(beside.occupancy().nodeCount(), inline_.occupancy().nodeCount());
  EXPECT_TRUE(beside.occupancy().binaryData() == inline_.occupancy().binaryData());  // not printed: 50 kB
  // Keyframe 3 moved 5 cm while the rebuild cast it where it was: the octree is due for another.
  EXPECT_TRUE(beside.octreeStale());
  EXPECT_TRUE(inline_.octreeStale());
  beside.flush();
  inline_.flush();
  EXPECT_FALSE(beside.octreeStale());
  EXPECT_TRUE(beside.occupancy().binaryData() == inline_.occupancy().binaryData());
}

// A mapper dropped (a new camera, a new tracker map, exit) while a rebuild runs stops it and waits for it.
TEST(PoseUpdate, AMapperDroppedWhileRebuildingStopsTheRebuild) {
  auto mapper = std::make_unique<Mapper>(test::testSettings());
  for (int id = 0; id < 30; ++id)
    ASSERT_TRUE(mapper->integrate(wallKeyframe(id, translation(0.3 * id, 0, 0), kWall)).ok);
  ASSERT_EQ(mapper->updatePoses({{0, translation(0.1, 0, 0)}}).applied, 1);
  mapper->maintain(100.0);
  ASSERT_TRUE(mapper->rebuilding());
  mapper.reset();
  EXPECT_EQ(mapper, nullptr);
}

TEST(PoseUpdate, UnknownIdsAndBadPosesAreRefusedOneByOne) {
  Mapper mapper(test::testSettings());
  ASSERT_TRUE(mapper.integrate(wallKeyframe(3, SE3::Identity(), kWall)).ok);
  SE3 bad = SE3::Identity();
  bad.translation().y() = std::numeric_limits<double>::infinity();
  const PoseUpdateResult r =
      mapper.updatePoses({{42, SE3::Identity()}, {3, bad}, {3, translation(0.1, 0, 0)}});
  EXPECT_EQ(r.applied, 1);
  ASSERT_EQ(r.rejected.size(), 2u);
  EXPECT_EQ(r.rejected[0], "keyframe 42: unknown keyframe");
  EXPECT_EQ(r.rejected[1], "keyframe 3: non-finite pose");
}

// A forged pose 1.6 km away would make the grid span it (64000^2 cells): refused, as a keyframe and as an
// update, and the grid keeps its size.
TEST(WorldRadius, KeyframesAndUpdatesBeyondItAreRefused) {
  MapperSettings settings = test::testSettings();
  settings.world_radius_m = 50.0;
  Mapper mapper(settings);
  ASSERT_TRUE(mapper.integrate(wallKeyframe(1, SE3::Identity(), kWall)).ok);
  const std::size_t cells = mapper.grid().cells.size();
  const IntegrateResult far = mapper.integrate(wallKeyframe(2, translation(1600.0, 0, 1600.0), kWall));
  EXPECT_FALSE(far.ok);
  EXPECT_EQ(far.reason, "pose 2262 m from the world origin, beyond world_radius_m 50");
  EXPECT_TRUE(mapper.integrate(wallKeyframe(3, translation(30.0, 0, 0), kWall)).ok);
  const PoseUpdateResult r = mapper.updatePoses({{1, translation(0, 0, 60.0)}, {3, translation(31.0, 0, 0)}});
  EXPECT_EQ(r.applied, 1);
  ASSERT_EQ(r.rejected.size(), 1u);
  EXPECT_EQ(r.rejected[0], "keyframe 1: pose 60 m from the world origin, beyond world_radius_m 50");
  EXPECT_EQ(mapper.keyframeCount(), 2u);
  EXPECT_GT(mapper.grid().cells.size(), cells);  // the one 30 m away widened it, within bounds
  EXPECT_LT(mapper.grid().cells.size(), 2000u * 2000u);
}

// A keyframe that saw nothing (all depth zero: another publisher's, 140 m away) does not widen the grid
// with its camera's disc, and a grid as wide as the world is drawn within the picture budget: two such
// keyframes made each save take 1.6 GB and 22 s.
TEST(WorldRadius, AKeyframeWithNoDepthDoesNotWidenTheGridAndAHugeGridIsDrawnSmall) {
  Mapper mapper(test::testSettings());
  ASSERT_TRUE(mapper.integrate(wallKeyframe(1, SE3::Identity(), kWall)).ok);
  const OccupancyGrid2D before = mapper.grid();
  KeyframeInput empty = wallKeyframe(2, translation(140.0, 0, 140.0), kWall);
  empty.depth.setTo(0);
  ASSERT_TRUE(mapper.integrate(empty).ok);
  const OccupancyGrid2D after = mapper.grid();
  EXPECT_EQ(after.width, before.width);
  EXPECT_EQ(after.height, before.height);
  const cv::Mat small = renderGrid(before, 4);
  EXPECT_EQ(small.cols, before.width * 4);
  EXPECT_EQ(small.rows, before.height * 4);
  EXPECT_EQ(small.at<cv::Vec3b>(small.rows - 1, 0), cv::Vec3b(128, 128, 128));
  OccupancyGrid2D huge;
  huge.width = 8000;
  huge.height = 2000;
  huge.cells.assign(static_cast<std::size_t>(huge.width) * huge.height, kCellFree);
  const cv::Mat drawn = renderGrid(huge, 4);
  EXPECT_EQ(drawn.cols, kMaxGridPicturePx);
  EXPECT_EQ(drawn.rows, kMaxGridPicturePx / 4);
  EXPECT_EQ(drawn.at<cv::Vec3b>(10, 10), cv::Vec3b(255, 255, 255));
}

// Forged keyframes with fresh ids at fresh places would grow memory without bound: once the map holds
// max_keyframes, only revisits (merged into a kept keyframe) are taken.
TEST(MaxKeyframes, BeyondItOnlyRevisitsAreTaken) {
  MapperSettings settings = test::testSettings();
  settings.max_keyframes = 2;
  Mapper mapper(settings);
  ASSERT_TRUE(mapper.integrate(wallKeyframe(1, SE3::Identity(), kWall)).ok);
  ASSERT_TRUE(mapper.integrate(wallKeyframe(2, translation(1.0, 0, 0), kWall)).ok);
  const IntegrateResult third = mapper.integrate(wallKeyframe(3, translation(2.0, 0, 0), kWall));
  EXPECT_FALSE(third.ok);
  EXPECT_EQ(third.reason, "the map holds max_keyframes (2) keyframes; only revisits of them are taken");
  const IntegrateResult revisit = mapper.integrate(wallKeyframe(4, translation(1.01, 0, 0), kWall));
  EXPECT_TRUE(revisit.ok) << revisit.reason;
  EXPECT_EQ(mapper.keyframeCount(), 2u);
  EXPECT_EQ(mapper.mergedCount(), 1u);
}

}  // namespace
}  // namespace bmp::mapper

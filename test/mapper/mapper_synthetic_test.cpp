// The synthetic dynamic scene (bmp_capture's SyntheticScene, no LCM): keyframes from every 10th frame with
// the ground-truth pose, exact depth and the ground-truth mask of the walking boxes. With masks on, almost no
// map point lies where the movers walked and no voxel on their paths is occupied; with masks off, clearly
// more points do. Walls, floor and furniture are in the cloud and occupied in the octree; space the camera
// saw is free.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <unordered_set>

#include "capture/synthetic_scene.hpp"
#include "mapper/mapper.hpp"

namespace bmp::mapper {
namespace {

constexpr int kEvery = 10;
constexpr double kCell = 0.02;  // footprint raster of the movers' swept volume

// Where the walking boxes have been (frames 0..last): their footprints on the floor, rastered, and their
// height. A point is "in the swept volume" when above the floor, below the boxes' top and over a footprint.
class SweptVolume {
 public:
  SweptVolume(const capture::SyntheticScene& scene, int last_frame, double margin) {
    for (int f = 0; f <= last_frame; ++f) {
      for (const auto& m : scene.movingObjects(f)) {
        top_ = std::max(top_, m.box.hi.z());
        const double reach = m.box.hi.head<2>().norm() + margin + kCell;
        for (double x = m.position.x() - reach; x <= m.position.x() + reach; x += kCell) {
          for (double y = m.position.y() - reach; y <= m.position.y() + reach; y += kCell) {
            const Eigen::Vector3d p_obj = m.T_world_object.inverse() * Eigen::Vector3d(x, y, 0.5);
            if ((p_obj.head<2>().array() >= m.box.lo.head<2>().array() - margin).all() &&
                (p_obj.head<2>().array() <= m.box.hi.head<2>().array() + margin).all())
              cells_.insert(key(x, y));
          }
        }
      }
    }
  }
  bool contains(const Eigen::Vector3d& p, double floor_clearance) const {
    return p.z() > floor_clearance && p.z() < top_ + 0.03 && cells_.count(key(p.x(), p.y())) != 0;
  }
  template <typename Fn>
  void forEachCell(Fn fn) const {
    for (const int64_t k : cells_)
      fn(((k >> 20) - (1 << 19)) * kCell + kCell / 2, ((k & 0xfffff) - (1 << 19)) * kCell + kCell / 2);
  }

 private:
  static int64_t key(double x, double y) {
    const int64_t i = static_cast<int64_t>(std::floor(x / kCell)) + (1 << 19);
    const int64_t j = static_cast<int64_t>(std::floor(y / kCell)) + (1 << 19);
    return (i << 20) | j;
  }
  std::unordered_set<int64_t> cells_;
  double top_ = 0;
};

struct SceneRun {
  std::unique_ptr<Mapper> mapper;
  std::vector<capture::SyntheticFrame> frames;
};

MapperSettings syntheticSettings() {
  MapperSettings s;
  s.grid.up = {0, 0, 1};  // the synthetic world: z up, floor at 0 (fitted, as by default)
  s.grid.height_min_m = 0.1;
  s.grid.height_max_m = 1.9;
  return s;
}

class SyntheticMap : public ::testing::Test {
 protected:
  // Each test case runs in a process of its own under ctest: rendering and mapping happen once per case,
  // so the cases are few and each checks much.
  static void SetUpTestSuite() {
    scene_ = std::make_unique<capture::SyntheticScene>(capture::SyntheticSceneConfig{});
    for (int f = 0; f < scene_->numFrames(); f += kEvery) frames_.push_back(scene_->render(f));
    masked_ = run(true);
  }
  static void TearDownTestSuite() {
    masked_.reset();
    unmasked_.reset();
    frames_.clear();
    scene_.reset();
  }
  static std::unique_ptr<Mapper> run(bool masks) {
    auto mapper = std::make_unique<Mapper>(syntheticSettings());
    for (const auto& f : frames_) {
      KeyframeInput kf;
      kf.id = f.index;
      kf.T_world_cam = f.T_world_cam;
      kf.camera = scene_->camera();
      kf.color = f.bgr;
      kf.depth = f.depth;
      if (masks) kf.dynamic_mask = f.mask;
      EXPECT_TRUE(mapper->integrate(kf).ok);
    }
    const TimingStats& t = mapper->integrationTimes();
    std::printf(
        "masks %s: %zu keyframes 640x480, integration median %.1f ms, p95 %.1f ms, %zu points, %zu nodes\n",
        masks ? "on" : "off", t.count(), t.median(), t.p95(), mapper->cloud().size(),
        mapper->occupancy().nodeCount());
    return mapper;
  }
  static double sweptShare(Mapper& mapper, const SweptVolume& swept) {
    std::size_t inside = 0;
    const PointList& cloud = mapper.cloud();
    for (const auto& p : cloud) inside += swept.contains(p.position().cast<double>(), 0.05);
    return static_cast<double>(inside) / static_cast<double>(cloud.size());
  }
  static int lastFrame() { return frames_.back().index; }
  void checkWallsFloorAndFurnitureAreMappedAndOccupied();
  void checkSpaceTheCameraSawIsFree();
  void checkNoVoxelOnAMoversPathIsOccupied();
  void checkFurnitureIsOccupiedInTheGrid();
  void checkTheFloorIsFitted();

  static std::unique_ptr<capture::SyntheticScene> scene_;
  static std::vector<capture::SyntheticFrame> frames_;
  static std::unique_ptr<Mapper> masked_, unmasked_;
};

std::unique_ptr<capture::SyntheticScene> SyntheticMap::scene_;
std::vector<capture::SyntheticFrame> SyntheticMap::frames_;
std::unique_ptr<Mapper> SyntheticMap::masked_;
std::unique_ptr<Mapper> SyntheticMap::unmasked_;

TEST_F(SyntheticMap, MasksKeepTheMoversOutOfTheCloud) {
  unmasked_ = run(false);
  const SweptVolume swept(*scene_, lastFrame(), 0.03);
  const double on = sweptShare(*masked_, swept), off = sweptShare(*unmasked_, swept);
  std::printf("share of map points in the movers' swept volume: masks on %.3f %%, off %.3f %%\n", 100 * on,
              100 * off);
  EXPECT_LT(on, 0.01);
  EXPECT_GT(off, 0.02);
  EXPECT_GT(off, 5 * on);
}

// Points of the cloud within 3 cm of a box face (the room from inside, furniture from outside).
std::vector<Eigen::Vector3d> onSurface(const PointList& cloud, const capture::AlignedBox& box, int axis,
                                       bool high) {
  std::vector<Eigen::Vector3d> out;
  for (const auto& p : cloud) {
    const Eigen::Vector3d q = p.position().cast<double>();
    const double face = high ? box.hi[axis] : box.lo[axis];
    bool within = std::abs(q[axis] - face) < 0.03;
    for (int a = 0; a < 3; ++a)
      if (a != axis) within = within && q[a] > box.lo[a] + 0.03 && q[a] < box.hi[a] - 0.03;
    if (within) out.push_back(q);
  }
  return out;
}

double occupiedShare(const Mapper& mapper, const std::vector<Eigen::Vector3d>& points) {
  std::size_t occupied = 0;
  for (const auto& p : points) occupied += mapper.occupancy().query(p) == Occupancy::kOccupied;
  return points.empty() ? 0.0 : static_cast<double>(occupied) / static_cast<double>(points.size());
}

void SyntheticMap::checkWallsFloorAndFurnitureAreMappedAndOccupied() {
  const PointList& cloud = masked_->cloud();
  const capture::AlignedBox& room = scene_->room();
  const auto floor = onSurface(cloud, room, 2, false);
  const auto far_wall = onSurface(cloud, room, 1, true);
  EXPECT_GT(floor.size(), 2000u);
  EXPECT_GT(far_wall.size(), 2000u);
  std::vector<Eigen::Vector3d> furniture;
  for (const auto& box : scene_->staticBoxes()) {
    for (int axis = 0; axis < 3; ++axis) {
      for (bool high : {false, true}) {
        const auto face = onSurface(cloud, box, axis, high);
        furniture.insert(furniture.end(), face.begin(), face.end());
      }
    }
  }
  EXPECT_GT(furniture.size(), 1000u);
  const double floor_share = occupiedShare(*masked_, floor), wall_share = occupiedShare(*masked_, far_wall),
               furniture_share = occupiedShare(*masked_, furniture);
  std::printf("occupied at cloud points: floor %.3f, far wall %.3f, furniture %.3f\n", floor_share,
              wall_share, furniture_share);
  EXPECT_GT(wall_share, 0.9);
  EXPECT_GT(furniture_share, 0.85);
  EXPECT_GT(floor_share, 0.75);  // rays graze the floor and carve part of its voxels: OctoMap's known limit
}

void SyntheticMap::checkSpaceTheCameraSawIsFree() {
  const SweptVolume swept(*scene_, lastFrame(), 0.15);
  std::size_t free = 0, checked = 0;
  for (const auto& f : frames_) {
    const CameraModel camera(scene_->camera());
    for (int v = 20; v < f.depth.rows; v += 40) {
      for (int u = 20; u < f.depth.cols; u += 40) {
        const double z = f.depth.at<uint16_t>(v, u) / scene_->camera().depth_scale;
        if (z < 0.6 || z > 5.0 || f.mask.at<uint8_t>(v, u) != 0) continue;
        const Eigen::Vector3d p = f.T_world_cam * camera.backProject(Eigen::Vector2d(u, v), 0.5 * z);
        if (swept.contains(p, -1.0)) continue;
        ++checked;
        free += masked_->occupancy().query(p) == Occupancy::kFree;
      }
    }
  }
  std::printf("free at half the measured depth: %zu of %zu\n", free, checked);
  ASSERT_GT(checked, 1000u);
  EXPECT_GT(static_cast<double>(free) / static_cast<double>(checked), 0.97);
}

void SyntheticMap::checkNoVoxelOnAMoversPathIsOccupied() {
  const SweptVolume swept(*scene_, lastFrame(), -0.05);  // the paths themselves, 5 cm inside the boxes
  std::size_t occupied = 0, checked = 0, grid_occupied = 0;
  const OccupancyGrid2D grid = masked_->grid();
  swept.forEachCell([&](double x, double y) {
    for (double z = 0.15; z < 1.6; z += 0.05) {
      ++checked;
      occupied += masked_->occupancy().query({x, y, z}) == Occupancy::kOccupied;
    }
    int col = 0, row = 0;
    if (grid.cellOf(grid.frame.planar({x, y, 0}), col, row))
      grid_occupied += grid.at(col, row) == kCellOccupied;
  });
  std::printf("voxels checked on the movers' paths: %zu, occupied %zu; grid cells occupied %zu\n", checked,
              occupied, grid_occupied);
  ASSERT_GT(checked, 10000u);
  EXPECT_EQ(occupied, 0u);
  EXPECT_EQ(grid_occupied, 0u);
}

void SyntheticMap::checkFurnitureIsOccupiedInTheGrid() {
  const OccupancyGrid2D grid = masked_->grid();
  std::size_t known = 0, occupied = 0;
  for (const auto& box : scene_->staticBoxes()) {
    // Cells inside the footprint, a cell clear of its edges: a seen piece of furniture blocks them all.
    for (double x = box.lo.x() + 0.05; x < box.hi.x() - 0.05; x += grid.resolution) {
      for (double y = box.lo.y() + 0.05; y < box.hi.y() - 0.05; y += grid.resolution) {
        int col = 0, row = 0;
        if (!grid.cellOf(grid.frame.planar({x, y, 0}), col, row) || grid.at(col, row) == kCellUnknown)
          continue;
        ++known;
        occupied += grid.at(col, row) == kCellOccupied;
      }
    }
  }
  std::printf("grid cells over furniture: %zu known, %zu occupied\n", known, occupied);
  ASSERT_GT(known, 100u);
  EXPECT_GT(static_cast<double>(occupied) / static_cast<double>(known), 0.9);
}

// The floor is at z = 0 with z up; furniture tops and the table are planes near up as well, with fewer
// points and higher: the lowest supported plane is the floor.
void SyntheticMap::checkTheFloorIsFitted() {
  const auto& floor = masked_->floor();
  ASSERT_TRUE(floor.has_value());
  const double tilt_deg = std::acos(std::min(1.0, floor->normal.z())) * 180.0 / M_PI;
  std::printf("fitted floor: tilt %.2f deg, height %.3f m, share %.2f\n", tilt_deg, floor->height,
              floor->share);
  EXPECT_LT(tilt_deg, 1.0);
  EXPECT_NEAR(floor->height, 0.0, 0.02);
  // A guess 20 degrees off (a camera looking down) still finds the same floor.
  const Eigen::Vector3d guess(0, std::sin(20 * M_PI / 180), std::cos(20 * M_PI / 180));
  const auto from_guess = fitFloor(masked_->cloud(), guess, masked_->settings().grid.floor);
  ASSERT_TRUE(from_guess.has_value());
  EXPECT_LT(std::acos(std::min(1.0, from_guess->normal.z())) * 180.0 / M_PI, 1.0);
  EXPECT_NEAR(from_guess->height, 0.0, 0.02);
  const GridSettings grounded = masked_->groundedGrid();
  EXPECT_NEAR(grounded.height_min_m, floor->height + 0.1, 1e-9);
}

TEST_F(SyntheticMap, MaskedMapHoldsTheStaticSceneAndNothingOfTheMovers) {
  {
    SCOPED_TRACE("walls, floor and furniture in the cloud and occupied");
    checkWallsFloorAndFurnitureAreMappedAndOccupied();
  }
  {
    SCOPED_TRACE("space the camera saw is free");
    checkSpaceTheCameraSawIsFree();
  }
  {
    SCOPED_TRACE("no voxel on a mover's path is occupied");
    checkNoVoxelOnAMoversPathIsOccupied();
  }
  {
    SCOPED_TRACE("furniture is occupied in the grid");
    checkFurnitureIsOccupiedInTheGrid();
  }
  {
    SCOPED_TRACE("the grid stands on the floor fitted in the cloud, also from a poor guess of up");
    checkTheFloorIsFitted();
  }
}

}  // namespace
}  // namespace bmp::mapper

// bmp-plan's A* on hand-made grids (walls, gaps, robot radius, unknown cells, corners), the map_server
// reader on the mapper's own files, and the bmp-plan executable on a map the mapper wrote.
#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <fstream>
#include <sstream>
#include <thread>
#include <utility>
#include <vector>

#include "bmp/common/atomic_file.hpp"
#include "bmp/common/child_process.hpp"
#include "bmp/common/config.hpp"
#include "bmp/lcm/lcm_node.hpp"
#include "lcm_url.hpp"
#include "mapper/grid_files.hpp"
#include "mapper/map_files.hpp"
#include "mapper_test_util.hpp"
#include "plan/astar.hpp"
#include "plan/live_grid.hpp"
#include "shared_data.hpp"

namespace bmp::plan {
namespace {

// width x height free cells of 0.1 m, origin (0, 0).
PlanGrid freeGrid(int width, int height) {
  PlanGrid g;
  g.resolution = 0.1;
  g.width = width;
  g.height = height;
  g.cells.assign(static_cast<std::size_t>(width) * height, kFree);
  return g;
}

void setCell(PlanGrid& g, int col, int row, int8_t value) {
  g.cells[static_cast<std::size_t>(row) * g.width + col] = value;
}

PlanOptions pointRobot() {
  PlanOptions o;
  o.robot_radius_m = 0.0;
  return o;
}

TEST(Astar, StraightLineOnAnOpenGrid) {
  const PlanResult r = planPath(freeGrid(40, 40), {0.55, 0.55}, {3.55, 0.55}, pointRobot());
  ASSERT_TRUE(r.found) << r.reason;
  EXPECT_NEAR(r.length_m, 3.0, 1e-9);
  EXPECT_EQ(r.cells.size(), 31u);
  const PlanResult diagonal = planPath(freeGrid(40, 40), {0.55, 0.55}, {3.55, 3.55}, pointRobot());
  EXPECT_NEAR(diagonal.length_m, 3.0 * std::sqrt(2.0), 1e-9);  // 8-connected: the diagonal is optimal
}

TEST(Astar, NoPathThroughAWallAndAroundItThroughAGap) {
  PlanGrid g = freeGrid(40, 40);
  for (int col = 0; col < 40; ++col) setCell(g, col, 20, kOccupied);
  const PlanResult blocked = planPath(g, {0.55, 1.05}, {0.55, 3.05}, pointRobot());
  EXPECT_FALSE(blocked.found);
  EXPECT_NE(blocked.reason.find("no collision-free path"), std::string::npos);
  for (int col = 30; col < 34; ++col) setCell(g, col, 20, kFree);  // a 0.4 m gap
  const PlanResult through = planPath(g, {0.55, 1.05}, {0.55, 3.05}, pointRobot());
  ASSERT_TRUE(through.found);
  EXPECT_GT(through.length_m, 2 * std::hypot(2.5, 1.0));  // no shorter than the detour by the gap at x = 3
  for (const auto& c : through.cells) EXPECT_NE(g.at(c.x(), c.y()), kOccupied);
  // A robot 0.5 m wide does not fit through 0.4 m.
  PlanOptions wide;
  wide.robot_radius_m = 0.25;
  EXPECT_FALSE(planPath(g, {0.55, 1.05}, {0.55, 3.05}, wide).found);
}

TEST(Astar, RobotRadiusKeepsThePathAwayFromObstacles) {
  PlanGrid g = freeGrid(40, 40);
  setCell(g, 20, 20, kOccupied);
  PlanOptions o;
  o.robot_radius_m = 0.3;
  const PlanResult r = planPath(g, {0.55, 2.05}, {3.55, 2.05}, o);
  ASSERT_TRUE(r.found);
  for (const auto& p : r.points) EXPECT_GT((p - g.centreOf(20, 20)).norm(), 0.3 - 1e-9);
  const PlanResult start_blocked = planPath(g, {2.15, 2.05}, {3.55, 2.05}, o);
  EXPECT_FALSE(start_blocked.found);
  EXPECT_NE(start_blocked.reason.find("start is blocked"), std::string::npos);
  EXPECT_NE(planPath(g, {-1, 0}, {1, 1}, o).reason.find("start lies outside"), std::string::npos);
}

TEST(Astar, UnknownCellsBlockUnlessToldOtherwise) {
  PlanGrid g = freeGrid(20, 20);
  for (int col = 0; col < 20; ++col) setCell(g, col, 10, kUnknown);
  EXPECT_FALSE(planPath(g, {0.55, 0.55}, {0.55, 1.95}, pointRobot()).found);
  PlanOptions o = pointRobot();
  o.unknown_is_blocked = false;
  EXPECT_TRUE(planPath(g, {0.55, 0.55}, {0.55, 1.95}, o).found);
}

TEST(Astar, DiagonalStepsDoNotCutCorners) {
  PlanGrid g = freeGrid(3, 3);
  setCell(g, 1, 0, kOccupied);
  setCell(g, 0, 1, kOccupied);
  // (0,0) touches (1,1) only through the corner between two obstacles.
  EXPECT_FALSE(planPath(g, {0.05, 0.05}, {0.15, 0.15}, pointRobot()).found);
}

TEST(MapServerReader, ReadsTheMappersGridBack) {
  const auto dir = test::scratchDir("plan_reader");
  mapper::OccupancyGrid2D grid;
  grid.resolution = 0.05;
  grid.width = 4;
  grid.height = 3;
  grid.origin = {-1.0, 2.5};
  grid.cells = {0, 100, -1, 0, 0, 0, 0, 0, 100, 100, -1, -1};
  writeFileAtomically((dir / "g.pgm").string(), mapper::encodePgm(grid));
  writeFileAtomically((dir / "g.yaml").string(), mapper::encodeMapYaml(grid, "g.pgm"));
  const PlanGrid read = readMapServerMap((dir / "g.yaml").string());
  EXPECT_EQ(read.width, 4);
  EXPECT_EQ(read.height, 3);
  EXPECT_NEAR(read.resolution, 0.05, 1e-9);
  EXPECT_NEAR(read.origin.x(), -1.0, 1e-9);
  EXPECT_NEAR(read.origin.y(), 2.5, 1e-9);
  EXPECT_EQ(read.cells, grid.cells);
  EXPECT_THROW(readMapServerMap((dir / "missing.yaml").string()), MapFileError);
  // A point far beyond the grid (or a tiny resolution) is outside it: its cell was cast from a double
  // beyond int's range (undefined; INT_MIN here).
  EXPECT_FALSE(read.inside(read.cellOf({1e300, 0}).x(), read.cellOf({1e300, 0}).y()));
  EXPECT_EQ(read.cellOf({1e300, -1e300}), Eigen::Vector2i(4, -1));
  EXPECT_EQ(read.cellOf({-0.99, 2.51}), Eigen::Vector2i(0, 0));
  // The plane's axes are keys, for programs that turn world poses into cells.
  grid.frame = mapper::PlaneFrame::fromUp({0.0, -0.970, -0.243});
  const Config yaml = Config::fromString(mapper::encodeMapYaml(grid, "g.pgm"), "g.yaml");
  const auto axis = [&](const char* key) {
    const auto v = yaml.get<std::vector<double>>(key, {});
    return v.size() == 3 ? Eigen::Vector3d(v[0], v[1], v[2]) : Eigen::Vector3d::Zero();
  };
  EXPECT_TRUE(axis("plane_x_axis").isApprox(grid.frame.x_axis, 1e-5));
  EXPECT_TRUE(axis("plane_y_axis").isApprox(grid.frame.y_axis, 1e-5));
  EXPECT_TRUE(axis("plane_up").isApprox(grid.frame.up, 1e-5));
}

// bmp-plan on files bmp_mapper wrote from a wall 3 m ahead (up is the camera's -y: the plane is x, z).
class PlanTool : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = test::scratchDir("plan_tool");
    mapper::Mapper m(mapper::test::testSettings());
    ASSERT_TRUE(m.integrate(mapper::test::wallKeyframe(0, SE3::Identity(), 3.02)).ok);
    mapper::writeMapFiles(dir.string(), m);
  }
  int plan(const std::string& from, const std::string& to, std::string& output) {
    return run({"--map", (dir / "occupancy.yaml").string(), "--from", from, "--to", to, "--robot-radius",
                "0.1", "--out", (dir / "path.png").string(), "--path-out", (dir / "path.txt").string()},
               output);
  }
  // bmp-plan with these arguments; its exit status, and what it printed in output.
  int run(std::vector<std::string> arguments, std::string& output) {
    const std::string log = (dir / "plan.log").string();
    arguments.insert(arguments.begin(), test::binPath("bmp-plan"));
    ChildProcess child(std::move(arguments), ChildProcess::Output::kFile, log);
    const auto status = child.wait(30);
    std::ifstream in(log);
    std::stringstream text;
    text << in.rdbuf();
    output = text.str();
    return status.value_or(-1);
  }
  std::filesystem::path dir;
};

TEST_F(PlanTool, FindsAPathBetweenFreeCellsAndNoneBeyondTheWall) {
  std::string out;
  EXPECT_EQ(plan("0,0.8", "0.6,2.2", out), 0) << out;
  EXPECT_NE(out.find("path length"), std::string::npos) << out;
  EXPECT_TRUE(std::filesystem::exists(dir / "path.png"));
  EXPECT_NE(test::readFirstLine((dir / "path.txt").string()).find("# x y"), std::string::npos);
  EXPECT_EQ(plan("0,0.8", "0,4.0", out), 1) << out;  // behind the wall: unknown, and the wall is in the way
  EXPECT_NE(out.find("no path"), std::string::npos) << out;
}

// A value out of its range is a usage error naming the option (exit 2), not a plan with no robot or with
// the first two of three numbers.
TEST_F(PlanTool, OptionValuesOutOfRangeAreUsageErrorsNamingTheOption) {
  const std::string map = (dir / "occupancy.yaml").string();
  for (const char* radius : {"-1", "nan", "inf"}) {
    std::string out;
    EXPECT_EQ(run({"--map", map, "--from", "0,0.8", "--to", "0.6,2.2", "--robot-radius", radius}, out), 2)
        << radius << ": " << out;
    EXPECT_NE(out.find("--robot-radius"), std::string::npos) << out;
  }
  for (const char* to : {"0,2,3", "0.6", "0.6,", "nan,2", "0.6;2.2"}) {
    std::string out;
    EXPECT_EQ(run({"--map", map, "--from", "0,0.8", "--to", to}, out), 2) << to << ": " << out;
    EXPECT_NE(out.find("--to"), std::string::npos) << out;
  }
  std::string out;
  EXPECT_EQ(run({"--map", map, "--from", "0,0.8", "--to", "0.6,2.2", "--robot-radius", "0"}, out), 0) << out;
}

// Arguments are all checked before a grid is read: --live with a bad --to waited for a grid and said "no
// grid" (3); an output folder that does not exist is a bad argument too.
TEST_F(PlanTool, BadArgumentsAreSaidBeforeAnyGridIsAwaited) {
  std::string out;
  EXPECT_EQ(run({"--live", "--lcm-url", "memq://", "--from", "0,0", "--to", "abc", "--timeout", "2"}, out), 2)
      << out;
  EXPECT_NE(out.find("--to"), std::string::npos) << out;
  EXPECT_EQ(out.find("no grid"), std::string::npos) << out;
  EXPECT_EQ(run({"--live", "--lcm-url", "memq://", "--from", "0,0", "--to", "1,1", "--timeout", "2", "--out",
                 (dir / "no_such_folder" / "p.png").string()},
                out),
            2)
      << out;
  EXPECT_NE(out.find("--out"), std::string::npos) << out;
  EXPECT_NE(out.find("no such folder"), std::string::npos) << out;
}

// A map file that is not there is said to be missing (yaml-cpp says "bad file"), exit 3; an output that
// cannot be written has its own status (4), after the path is printed: 1 means "no path".
TEST_F(PlanTool, AMissingMapAndAnUnwrittenOutputHaveTheirOwnStatus) {
  std::string out;
  const std::string missing = (dir / "missing.yaml").string();
  EXPECT_EQ(run({"--map", missing, "--from", "0,0.8", "--to", "0.6,2.2"}, out), 3) << out;
  EXPECT_NE(out.find(missing + ": no such file"), std::string::npos) << out;
  // A broken map file is no grid too (status 3, named), not yaml-cpp's words with the status for "no path".
  const std::pair<std::string, std::string> broken[] = {
      {"just a line of text\n", "not a map description"},
      {"image: g.pgm\nresolution: abc\norigin: [0, 0, 0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: "
       "0.2\n",
       "key 'resolution' must be a number"},
      {"image: g.pgm\nresolution: 0.05\norigin: [0, x, 0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: "
       "0.2\n",
       "key 'origin' must be a number"}};
  for (const auto& [text, message] : broken) {
    const std::string path = (dir / "broken.yaml").string();
    writeFileAtomically(path, text);
    EXPECT_EQ(run({"--map", path, "--from", "0,0.8", "--to", "0.6,2.2"}, out), 3) << out;
    EXPECT_NE(out.find(path + ": " + message), std::string::npos) << out;
  }
  // A name no file can take is a bad argument, found before planning.
  const std::string too_long = (dir / (std::string(300, 'p') + ".txt")).string();
  const std::string map = (dir / "occupancy.yaml").string();
  EXPECT_EQ(run({"--map", map, "--from", "0,0.8", "--to", "0.6,2.2", "--path-out", too_long}, out), 2) << out;
  EXPECT_NE(out.find("--path-out"), std::string::npos) << out;
  // /proc takes no new file. As root its folder passes the check (access() grants root everything) and the
  // write itself fails: status 4, after the path; otherwise the check refuses it.
  const bool root = ::geteuid() == 0;
  EXPECT_EQ(
      run({"--map", map, "--from", "0,0.8", "--to", "0.6,2.2", "--path-out", "/proc/bmp_plan_path.txt"}, out),
      root ? 4 : 2)
      << out;
  if (root) {
    EXPECT_NE(out.find("path length"), std::string::npos) << out;
    EXPECT_NE(out.find("not written"), std::string::npos) << out;
  }
}

occupancy_grid_t gridMessage(int width, int height) {
  occupancy_grid_t m{};
  m.resolution = 0.05f;
  m.width = width;
  m.height = height;
  m.num_cells = width * height;
  m.cells.assign(static_cast<std::size_t>(m.num_cells), kFree);
  m.origin.position[0] = 1.0;
  m.origin.orientation[0] = 1.0;  // w first, identity
  return m;
}

// OCCUPANCY_GRID is open to any publisher: sizes, resolution and origin are checked before use.
TEST(LiveGrid, AnInconsistentGridIsRefusedWithTheReason) {
  const PlanGrid good = planGridFromMessage(gridMessage(4, 3));
  EXPECT_EQ(good.width, 4);
  EXPECT_NEAR(good.origin.x(), 1.0, 1e-9);
  occupancy_grid_t cells = gridMessage(4, 3), nan_origin = cells, inf_resolution = cells, quaternion = cells;
  cells.num_cells = 11;
  nan_origin.origin.position[1] = std::nan("");
  inf_resolution.resolution = INFINITY;
  quaternion.origin.orientation[0] = 0.0;
  EXPECT_THROW(planGridFromMessage(cells), MapFileError);
  EXPECT_THROW(planGridFromMessage(inf_resolution), MapFileError);
  const std::pair<occupancy_grid_t, const char*> origins[] = {
      {nan_origin, "origin: non-finite pose"}, {quaternion, "origin: pose quaternion is not a unit"}};
  for (const auto& [m, reason] : origins) {
    try {
      planGridFromMessage(m);
      ADD_FAILURE() << "an unusable origin was taken";
    } catch (const MapFileError& e) {
      EXPECT_NE(std::string(e.what()).find(reason), std::string::npos) << e.what();
    }
  }
}

// bmp-plan --live: an unusable grid (another publisher's) is waited past, not taken as "no grid".
TEST(LiveGrid, AnUnusableGridIsWaitedPastForAGoodOne) {
  const std::string url = test::uniqueLcmUrl(5);
  std::atomic<bool> done{false};
  std::thread publisher([&] {
    LcmNode node(url);
    occupancy_grid_t bad = gridMessage(4, 3);
    bad.num_cells = 5;
    const occupancy_grid_t good = gridMessage(7, 2);
    for (int round = 0; round < 200 && !done; ++round) {
      node.publish("GRID", bad);  // first, every round
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      if (round >= 5) node.publish("GRID", good);
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  });
  PlanGrid got;
  try {
    got = receiveLiveGrid(url, "GRID", 10.0);
  } catch (const MapFileError& e) {
    ADD_FAILURE() << e.what();
  }
  done = true;
  publisher.join();
  EXPECT_EQ(got.width, 7);
  EXPECT_EQ(got.height, 2);
}

}  // namespace
}  // namespace bmp::plan

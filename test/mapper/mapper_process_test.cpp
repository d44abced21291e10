// The real bmp-mapper over LCM: keyframes, a pose update and bad input in; the grid out; the map files on
// SIGUSR1 and again on SIGINT, with the counts of its heartbeat.
#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <thread>
#include <vector>

#include <pcl/io/pcd_io.h>
#include <pcl/point_types.h>

#include <bmp/keyframe_poses_t.hpp>
#include <bmp/occupancy_grid_t.hpp>
#include <bmp/process_status_t.hpp>

#include "bmp/common/child_process.hpp"
#include "bmp/lcm/lcm_node.hpp"
#include "keyframe_message_util.hpp"
#include "lcm_url.hpp"
#include "mapper_test_util.hpp"
#include "plan/plan_grid.hpp"
#include "shared_data.hpp"

namespace bmp::mapper {
namespace {

namespace fs = std::filesystem;

class MapperUnderTest {
 public:
  // prepare, when given, fills the fresh scratch folder before the mapper starts (a map left there).
  explicit MapperUnderTest(const std::function<void(const fs::path& map_dir)>& prepare = {})
      : url_(bmp::test::uniqueLcmUrl(0)), dir_(bmp::test::scratchDir("mapper_process")), node_(url_) {
    if (prepare) prepare(dir_ / "map");
    node_.subscribe<process_status_t>("PROCESS_STATUS",
                                      [this](const process_status_t& m, const ReceivedInfo&) {
                                        if (m.name == "bmp-mapper") status = m;
                                      });
    node_.subscribe<occupancy_grid_t>("OCCUPANCY_GRID",
                                      [this](const occupancy_grid_t& m, const ReceivedInfo&) { grid = m; });
    child_ = std::make_unique<ChildProcess>(
        std::vector<std::string>{bmp::test::binPath("bmp-mapper"), "--config",
                                 bmp::test::sourceDir() + "/config/mapper.yaml", "--lcm-url", url_, "--out",
                                 (dir_ / "map").string()},
        ChildProcess::Output::kFile, logPath());
  }
  bool pumpUntil(const std::function<bool()>& done, double timeout_s) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
    while (!done() && std::chrono::steady_clock::now() < end) node_.handle(20);
    return done();
  }
  template <typename Msg>
  void publish(const std::string& channel, const Msg& m) {
    node_.publish(channel, m);
  }
  std::string log() const {
    std::ifstream in(logPath());
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }
  std::string logPath() const { return (dir_ / "bmp-mapper.log").string(); }
  fs::path mapDir() const { return dir_ / "map"; }
  ChildProcess& child() { return *child_; }

  std::optional<process_status_t> status;
  std::optional<occupancy_grid_t> grid;

 private:
  std::string url_;
  fs::path dir_;
  LcmNode node_;
  std::unique_ptr<ChildProcess> child_;
};

TEST(MapperProcess, MapsKeyframesRefusesBadInputAndSavesOnSignals) {
  MapperUnderTest m;
  ASSERT_TRUE(m.pumpUntil([&] { return m.status.has_value() || !m.child().running(); }, 30)) << m.log();
  ASSERT_TRUE(m.child().running()) << m.log();

  // A forged keyframe of another camera before the tracker's first: the real ones replace its camera, and
  // the map started with it is dropped. Once the real camera settled (3 keyframes), another is refused.
  // Before it settled, another camera's keyframe that the new map would refuse (a pose 500 m away) is
  // refused without dropping the real map.
  keyframe_t forged = test::keyframeMessage(test::wallKeyframe(500, test::translation(0, 0, 1.0), 3.02));
  forged.camera.fx *= 1.5;
  m.publish("SLAM_KEYFRAME", forged);
  keyframe_t far = forged;
  far.id = 502;
  far.T_world_cam = toMsg(test::translation(500, 0, 0));
  for (int id = 0; id < 3; ++id) {
    m.publish("SLAM_KEYFRAME",
              test::keyframeMessage(test::wallKeyframe(id, test::translation(0.2 * id, 0, 0), 3.02)));
    if (id == 0) m.publish("SLAM_KEYFRAME", far);
  }
  forged.id = 501;
  m.publish("SLAM_KEYFRAME", forged);
  keyframe_t corrupt = test::keyframeMessage(test::wallKeyframe(3, SE3::Identity(), 3.02));
  for (std::size_t i = 40; i < corrupt.depth.data.size(); ++i) corrupt.depth.data[i] = 0x5a;
  m.publish("SLAM_KEYFRAME", corrupt);
  keyframe_poses_t poses;
  poses.utime = 5000000;
  poses.num_keyframes = 2;
  poses.ids = {1, 99};
  poses.T_world_cam = {toMsg(test::translation(0.5, 0, 0)), toMsg(SE3::Identity())};
  m.publish("SLAM_KEYFRAME_POSES", poses);
  keyframe_poses_t replayed = poses;  // an older optimisation's pose for keyframe 1, after the newer one
  replayed.utime = 4000000;
  replayed.num_keyframes = 1;
  replayed.ids = {1};
  replayed.T_world_cam = {toMsg(test::translation(9, 0, 0))};
  m.publish("SLAM_KEYFRAME_POSES", replayed);

  // 4 keyframes (the replaced one among them) and the pose message processed; the far one, the second
  // forged keyframe, the corrupt one, the unknown id and the older pose counted as malformed. The map holds
  // the 3 real keyframes.
  ASSERT_TRUE(m.pumpUntil(
      [&] {
        return m.status && m.status->processed >= 5 && m.status->malformed >= 5 &&
               m.status->message.find("keyframes 3") != std::string::npos;
      },
      20))
      << m.log();
  EXPECT_EQ(m.status->received, 9);
  EXPECT_EQ(m.status->processed, 5);
  EXPECT_EQ(m.status->malformed, 5);
  EXPECT_NE(m.status->message.find("keyframes 3"), std::string::npos) << m.status->message;
  EXPECT_NE(m.status->message.find("octree nodes"), std::string::npos) << m.status->message;
  ASSERT_TRUE(m.pumpUntil([&] { return m.grid.has_value(); }, 10));
  EXPECT_EQ(m.grid->num_cells, m.grid->width * m.grid->height);

  m.child().signal(SIGUSR1);
  ASSERT_TRUE(m.pumpUntil([&] { return fs::exists(m.mapDir() / "occupancy.png"); }, 20)) << m.log();
  EXPECT_TRUE(m.child().running());
  EXPECT_EQ(m.child().stop(20.0), 0) << m.log();

  const std::string log = m.log();
  EXPECT_NE(log.find("keyframe 3: depth does not decode"), std::string::npos) << log;
  EXPECT_NE(
      log.find("which came with only 1 message(s); starting again with this one; dropping the 1 keyframe(s)"),
      std::string::npos)
      << log;
  EXPECT_NE(log.find("keyframe 501: camera changed mid-run"), std::string::npos) << log;
  EXPECT_NE(log.find("keyframe 502: pose 500 m from the world origin"), std::string::npos) << log;
  EXPECT_NE(log.find("pose update for keyframe 99: unknown keyframe"), std::string::npos) << log;
  EXPECT_NE(log.find("pose update for keyframe 1: stamped 4000000 us, older than its pose of 5000000 us"),
            std::string::npos)
      << log;
  EXPECT_NE(log.find("map saved (SIGUSR1)"), std::string::npos) << log;
  EXPECT_NE(log.find("map saved (exit)"), std::string::npos) << log;
  for (const char* name : {"map.pcd", "map.ply", "map.bt", "occupancy.pgm", "occupancy.yaml", "cloud_top.png",
                           "cloud_oblique.png", "occupancy.png"})
    EXPECT_GT(fs::file_size(m.mapDir() / name), 50u) << name;
  const plan::PlanGrid grid = plan::readMapServerMap((m.mapDir() / "occupancy.yaml").string());
  const Eigen::Vector2i wall = grid.cellOf({0.0, 3.025});
  ASSERT_TRUE(grid.inside(wall.x(), wall.y()));
  EXPECT_EQ(grid.at(wall.x(), wall.y()), plan::kOccupied);

  // The last heartbeat (what the run summary prints) gives the points in the files, not the working
  // cloud's, which still holds points the filter and carving drop before a save.
  ASSERT_TRUE(m.pumpUntil([&] { return m.status->state == process_status_t::STATE_FINISHED; }, 10));
  const std::string pcd = bmp::test::readText((m.mapDir() / "map.pcd").string());
  const std::size_t at = pcd.find("\nPOINTS ");
  ASSERT_NE(at, std::string::npos);
  const std::string saved = "points " + std::to_string(std::stoll(pcd.substr(at + 8))) + " saved";
  EXPECT_NE(m.status->message.find(saved), std::string::npos) << saved << " / " << m.status->message;
}

// A map folder that cannot be made (a plain file in its place) stops the mapper at start-up, naming it,
// instead of mapping a whole run and losing the map at exit.
TEST(MapperProcess, UnwritableMapFolderFailsAtStartUp) {
  const fs::path dir = bmp::test::scratchDir("mapper_unwritable");
  std::ofstream(dir / "map") << "not a folder";
  ChildProcess child(
      {bmp::test::binPath("bmp-mapper"), "--config", bmp::test::sourceDir() + "/config/mapper.yaml",
       "--lcm-url", "memq://", "--out", (dir / "map").string()},
      ChildProcess::Output::kFile, (dir / "log").string());
  const std::optional<int> status = child.wait(30);
  const std::string log = bmp::test::readText((dir / "log").string());
  ASSERT_TRUE(status.has_value()) << log;
  EXPECT_EQ(*status, 1) << log;
  EXPECT_NE(log.find((dir / "map").string() + ": cannot create the map folder"), std::string::npos) << log;
}

// The save at exit failing (the folder replaced by a file while it ran) is the mapper's failure: a run
// that lost its map must not report success.
TEST(MapperProcess, FailedSaveAtExitIsANonZeroExit) {
  MapperUnderTest m;
  ASSERT_TRUE(m.pumpUntil([&] { return m.status.has_value() || !m.child().running(); }, 30)) << m.log();
  ASSERT_TRUE(m.child().running()) << m.log();
  fs::remove_all(m.mapDir());
  std::ofstream(m.mapDir()) << "not a folder";
  EXPECT_EQ(m.child().stop(20.0), 1) << m.log();
  EXPECT_NE(m.log().find("map not saved (exit)"), std::string::npos) << m.log();
}

// The tracker restarted mid-run: its new map's keyframes start again at id 0, at the origin of a new world
// frame. They were refused as already mapped up to the old map's last id and merged into it after that,
// in the wrong frame. The map so far is saved in its own folder and the new one starts from keyframe 0. The
// folder holds an earlier run's tracker_map_1 (this mapper was restarted): it is kept, and the map goes to
// tracker_map_2 (each run counted from 1, and replaced the earlier run's).
TEST(MapperProcess, ATrackerThatBeganANewMapGetsANewMapAndTheOldOneIsKept) {
  const std::string earlier_run = "# an earlier run's map set aside\n";
  MapperUnderTest m([&](const fs::path& map_dir) {
    fs::create_directories(map_dir / "tracker_map_1");
    std::ofstream(map_dir / "tracker_map_1" / "map.pcd") << earlier_run;
  });
  ASSERT_TRUE(m.pumpUntil([&] { return m.status.has_value() || !m.child().running(); }, 30)) << m.log();
  for (int id = 0; id < 3; ++id)
    m.publish("SLAM_KEYFRAME",
              test::keyframeMessage(test::wallKeyframe(id, test::translation(0.2 * id, 0, 0), 3.02)));
  ASSERT_TRUE(
      m.pumpUntil([&] { return m.status && m.status->message.find("keyframes 3") != std::string::npos; }, 20))
      << m.log();
  // The restarted tracker's world: the wall 2 m ahead of its origin. A keyframe 0 that is not at the origin
  // is no tracker's first, and is refused as mapped already.
  m.publish("SLAM_KEYFRAME", test::keyframeMessage(test::wallKeyframe(0, test::translation(0.1, 0, 0), 2.0)));
  for (int id = 0; id < 2; ++id)
    m.publish("SLAM_KEYFRAME",
              test::keyframeMessage(test::wallKeyframe(id, test::translation(0.2 * id, 0, 0), 2.0)));
  ASSERT_TRUE(m.pumpUntil(
      [&] {
        return m.status && m.status->processed >= 5 &&
               m.status->message.find("keyframes 2") != std::string::npos;
      },
      20))
      << m.log();
  EXPECT_EQ(m.status->malformed, 1);
  EXPECT_EQ(m.child().stop(20.0), 0) << m.log();
  const std::string log = m.log();
  const fs::path earlier = m.mapDir() / "tracker_map_2";
  EXPECT_EQ(bmp::test::readText((m.mapDir() / "tracker_map_1" / "map.pcd").string()), earlier_run);
  EXPECT_NE(log.find("the tracker began a new map (restarted); the map so far (3 keyframes) is saved in " +
                     earlier.string()),
            std::string::npos)
      << log;
  EXPECT_NE(log.find("keyframe 0: a keyframe with this id was already mapped"), std::string::npos) << log;
  // Both maps on disk: the earlier one's wall at 3.02 m, the new one's at 2 m (the camera looks along z).
  const auto wallDepth = [](const fs::path& pcd) {
    pcl::PointCloud<pcl::PointXYZRGB> cloud;
    if (pcl::io::loadPCDFile(pcd.string(), cloud) != 0 || cloud.empty()) return -1.0;
    double sum = 0;
    for (const auto& p : cloud) sum += p.z;
    return sum / static_cast<double>(cloud.size());
  };
  EXPECT_NEAR(wallDepth(earlier / "map.pcd"), 3.02, 0.05);
  EXPECT_NEAR(wallDepth(m.mapDir() / "map.pcd"), 2.0, 0.05);
}

// Keyframes that come faster than the mapper maps them (60 VGA keyframes of noise, 0.9 MB each, every
// 20 ms; the mapper takes tens of ms for each) wait in its inbox and are all mapped. Read from the mapper's
// loop, they waited in LCM's own queue, which holds 30 messages a subscription and drops the rest without
// a word: 45 and 46 of 60 mapped in two runs, and the heartbeat said nothing was dropped.
TEST(MapperProcess, KeyframesThatComeFasterThanItMapsWaitAndAreAllMapped) {
  MapperUnderTest m;
  ASSERT_TRUE(m.pumpUntil([&] { return m.status.has_value() || !m.child().running(); }, 30)) << m.log();
  ASSERT_TRUE(m.child().running()) << m.log();
  constexpr int kKeyframes = 60;
  cv::RNG rng(7);
  std::vector<keyframe_t> burst;
  for (int id = 0; id < kKeyframes; ++id) {
    KeyframeInput kf = test::wallKeyframe(id, test::translation(0.3 * id, 0, 0), 3.02);
    kf.camera.width = 640;
    kf.camera.height = 480;
    kf.camera.fx = kf.camera.fy = 525.0;
    kf.camera.cx = 319.5;
    kf.camera.cy = 239.5;
    kf.color.create(480, 640, CV_8UC3);
    rng.fill(kf.color, cv::RNG::UNIFORM, 0, 256);  // noise: JPEG and PNG cannot shrink it
    kf.depth.create(480, 640, CV_16UC1);
    rng.fill(kf.depth, cv::RNG::UNIFORM, 2900, 3100);
    kf.dynamic_mask = cv::Mat::zeros(480, 640, CV_8UC1);
    burst.push_back(test::keyframeMessage(kf));
  }
  ASSERT_GT(burst.front().color.size + burst.front().depth.size, 500000);
  for (const auto& kf : burst) {
    m.publish("SLAM_KEYFRAME", kf);
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  // Once nothing more comes for 10 s, whatever the mapper's pace: the count is what was lost.
  int64_t processed = -1;
  auto last_change = std::chrono::steady_clock::now();
  m.pumpUntil(
      [&] {
        if (m.status && m.status->processed != processed) {
          processed = m.status->processed;
          last_change = std::chrono::steady_clock::now();
        }
        return processed >= kKeyframes ||
               std::chrono::steady_clock::now() - last_change > std::chrono::seconds(10);
      },
      120);
  ASSERT_TRUE(m.status) << m.log();
  EXPECT_EQ(m.status->processed, kKeyframes);
  EXPECT_EQ(m.status->dropped, 0);
  EXPECT_EQ(m.status->malformed, 0);
  EXPECT_EQ(m.child().stop(20.0), 0) << m.log();
}

// Restarted on a folder that holds a map and stopped before any keyframe came (the tracker down, or every
// keyframe refused): the map there stays as it was. The exit's save once replaced it with an empty one.
TEST(MapperProcess, StoppedBeforeAnyKeyframeItLeavesAMapInTheFolderAsItWas) {
  const std::string yesterday = "# yesterday's map: not to be replaced by an empty one\n";
  MapperUnderTest m([&](const fs::path& map_dir) {
    fs::create_directories(map_dir);
    for (const char* name : {"map.pcd", "map.bt", "occupancy.yaml"})
      std::ofstream(map_dir / name) << yesterday;
  });
  ASSERT_TRUE(m.pumpUntil([&] { return m.status.has_value() || !m.child().running(); }, 30)) << m.log();
  ASSERT_TRUE(m.child().running()) << m.log();
  EXPECT_EQ(m.child().stop(20.0), 0) << m.log();
  for (const char* name : {"map.pcd", "map.bt", "occupancy.yaml"})
    EXPECT_EQ(bmp::test::readText((m.mapDir() / name).string()), yesterday) << name;
  EXPECT_FALSE(fs::exists(m.mapDir() / "map.ply"));
  EXPECT_NE(m.log().find("no keyframe mapped in this run: the map already in " + m.mapDir().string() +
                         " is left as it was"),
            std::string::npos)
      << m.log();
}

}  // namespace
}  // namespace bmp::mapper

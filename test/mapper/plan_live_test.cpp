// The real bmp-plan --live: it plans on an OCCUPANCY_GRID message this test publishes (a grid the mapper
// library made from a wall 3 m ahead, sent as bmp-mapper sends it), and without one it gives up after
// --timeout with its own exit status and says why.
#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <sstream>
#include <thread>

#include "bmp/common/child_process.hpp"
#include "bmp/lcm/lcm_node.hpp"
#include "lcm_url.hpp"
#include "mapper/lcm/mapper_messages.hpp"
#include "mapper/mapper.hpp"
#include "mapper_test_util.hpp"
#include "shared_data.hpp"

namespace bmp::plan {
namespace {

class PlanLive : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = bmp::test::scratchDir("plan_live");
    mapper::Mapper m(mapper::test::testSettings());
    ASSERT_TRUE(m.integrate(mapper::test::wallKeyframe(0, SE3::Identity(), 3.02)).ok);
    grid = mapper::toGridMessage(m.grid(), 1000000);
  }
  std::unique_ptr<ChildProcess> start(const std::string& from, const std::string& to,
                                      const std::string& timeout) {
    return std::make_unique<ChildProcess>(
        std::vector<std::string>{bmp::test::binPath("bmp-plan"), "--live", "--lcm-url", url, "--from", from,
                                 "--to", to, "--robot-radius", "0.1", "--timeout", timeout, "--out",
                                 (dir / "path.png").string()},
        ChildProcess::Output::kFile, (dir / "plan.log").string());
  }
  // Publishes the grid every 0.2 s, as a running bmp-mapper repeats it, until bmp-plan ends.
  std::optional<int> publishUntilExit(ChildProcess& child, double timeout_s) {
    LcmNode node(url);
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
    while (child.running() && std::chrono::steady_clock::now() < end) {
      node.publish("OCCUPANCY_GRID", grid);
      std::this_thread::sleep_for(std::chrono::milliseconds(200));
    }
    return child.wait(1.0);
  }
  std::string log() const {
    std::ifstream in(dir / "plan.log");
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }
  std::filesystem::path dir;
  std::string url = bmp::test::uniqueLcmUrl(1);
  occupancy_grid_t grid;
};

TEST_F(PlanLive, PlansOnThePublishedGridAndExitsZero) {
  auto child = start("0,0.8", "0.6,2.2", "20");
  EXPECT_EQ(publishUntilExit(*child, 30).value_or(-1), 0) << log();
  EXPECT_NE(log().find("path length"), std::string::npos) << log();
  EXPECT_TRUE(std::filesystem::exists(dir / "path.png"));
}

TEST_F(PlanLive, NoPathBeyondTheWallExitsOne) {
  auto child = start("0,0.8", "0,4.0", "20");
  EXPECT_EQ(publishUntilExit(*child, 30).value_or(-1), 1) << log();
  EXPECT_NE(log().find("no path"), std::string::npos) << log();
}

TEST_F(PlanLive, WithoutAGridItGivesUpAfterTheTimeoutWithStatusThree) {
  const auto started = std::chrono::steady_clock::now();
  auto child = start("0,0.8", "0.6,2.2", "1.5");
  EXPECT_EQ(child->wait(20).value_or(-1), 3) << log();
  const double took = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  EXPECT_GT(took, 1.4);
  EXPECT_LT(took, 10.0);
  EXPECT_NE(log().find("no grid: no OCCUPANCY_GRID message within 1.5 s"), std::string::npos) << log();
  EXPECT_FALSE(std::filesystem::exists(dir / "path.png"));
}

}  // namespace
}  // namespace bmp::plan

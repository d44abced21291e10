#include <gtest/gtest.h>

#include <bmp/slam_pose_t.hpp>

#include "bmp/lcm/conversions.hpp"
#include "bmp/lcm/lcm_node.hpp"
#include "lcm_url.hpp"

namespace bmp {
namespace {

TEST(LcmNode, ReceiveBufferLargerThanTheKernelAllowsIsWarned) {
  const std::string url = "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=4194304";
  const std::string w = receiveBufferWarning(url, 212992);  // Debian's default
  EXPECT_NE(w.find("net.core.rmem_max is 212992"), std::string::npos) << w;
  EXPECT_NE(w.find("sysctl -w net.core.rmem_max=4194304"), std::string::npos) << w;
  EXPECT_EQ(receiveBufferWarning(url, 4194304), "");
  EXPECT_EQ(receiveBufferWarning("udpm://239.255.76.67:7667?ttl=0", 212992), "");  // asks for nothing
  EXPECT_EQ(receiveBufferWarning("memq://", 1), "");
}

// A udpm URL without a receive buffer would get the kernel's 208 KiB, and a 640x480 frame (about 1 MB)
// would be lost whenever it arrives faster than it is read.
TEST(LcmNode, AUdpmUrlWithoutAReceiveBufferGetsTheDefaultOne) {
  EXPECT_EQ(withReceiveBuffer("udpm://239.255.76.67:7691?ttl=0"),
            "udpm://239.255.76.67:7691?ttl=0&recv_buf_size=4194304");
  EXPECT_EQ(withReceiveBuffer("udpm://239.255.76.67:7691"),
            "udpm://239.255.76.67:7691?recv_buf_size=4194304");
  EXPECT_EQ(withReceiveBuffer("udpm://239.255.76.67:7691?"),
            "udpm://239.255.76.67:7691?recv_buf_size=4194304");
  // A size the user chose, and other providers, are left alone.
  EXPECT_EQ(withReceiveBuffer("udpm://239.255.76.67:7691?recv_buf_size=65536&ttl=1"),
            "udpm://239.255.76.67:7691?recv_buf_size=65536&ttl=1");
  EXPECT_EQ(withReceiveBuffer("memq://"), "memq://");
  EXPECT_EQ(withReceiveBuffer("file:///tmp/x.lcmlog?mode=r"), "file:///tmp/x.lcmlog?mode=r");
  // The default URL already names the default size, so it is its own completion.
  EXPECT_EQ(withReceiveBuffer(kDefaultLcmUrl), kDefaultLcmUrl);
  EXPECT_NE(std::string(kDefaultLcmUrl).find("recv_buf_size=" + std::to_string(kDefaultReceiveBufferBytes)),
            std::string::npos);
  EXPECT_EQ(resolveLcmUrl("udpm://239.255.76.67:7691?ttl=0"),
            "udpm://239.255.76.67:7691?ttl=0&recv_buf_size=4194304");
  // LCM takes the completed form of a bare address.
  const std::string url = test::uniqueLcmUrl(0);
  const std::string bare = url.substr(0, url.find('?'));
  EXPECT_NO_THROW(LcmNode(withReceiveBuffer(bare), [](const std::string&) {}));
}

TEST(LcmNode, TypedRoundTripOverMemq) {
  LcmNode node("memq://");
  std::vector<slam_pose_t> got;
  node.subscribe<slam_pose_t>("POSE", [&](const slam_pose_t& m, const ReceivedInfo& info) {
    got.push_back(m);
    EXPECT_EQ(info.channel, "POSE");
  });
  slam_pose_t msg{};
  msg.seq = 17;
  msg.T_world_cam =
      toMsg(makeSE3({1, 2, 3}, Eigen::Quaterniond(Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ()))));
  node.publish("POSE", msg);
  node.handle(100);
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0].seq, 17);
  EXPECT_LT((fromMsg(got[0].T_world_cam).translation() - Eigen::Vector3d(1, 2, 3)).norm(), 1e-12);
}

// LCM subscribes by regular expression: a configured channel name that is not one is an error naming it
// (it crashed the process: LCM returned no subscription).
TEST(LcmNode, AChannelNameThatIsNoValidPatternIsAnErrorNamingIt) {
  LcmNode node("memq://", [](const std::string&) {});
  try {
    node.subscribe<slam_pose_t>("SLAM_POSE[", [](const slam_pose_t&, const ReceivedInfo&) {});
    FAIL() << "subscribed";
  } catch (const LcmError& e) {
    EXPECT_NE(std::string(e.what()).find("channel 'SLAM_POSE['"), std::string::npos) << e.what();
  }
  EXPECT_THROW(node.subscribeRaw("SLAM_(POSE", [](const void*, uint32_t, const ReceivedInfo&) {}), LcmError);
  EXPECT_THROW(checkChannelName(""), LcmError);
  EXPECT_THROW(checkChannelName(std::string(64, 'A')), LcmError) << "LCM's limit is 63 bytes";
  EXPECT_NO_THROW(checkChannelName(std::string(63, 'A')));
  EXPECT_NO_THROW(checkChannelName("robot1/SLAM_POSE.v2-a:b"));
}

// Another publisher's bytes on our channel must be reported and skipped, never crash or reach the handler.
TEST(LcmNode, MalformedMessageIsCountedAndNamed) {
  std::vector<std::string> warnings;
  LcmNode node("memq://", [&](const std::string& w) { warnings.push_back(w); });
  int calls = 0;
  node.subscribe<slam_pose_t>("SLAM_POSE", [&](const slam_pose_t&, const ReceivedInfo&) { ++calls; });
  const char garbage[] = "definitely not an LCM-encoded slam_pose_t";
  node.raw().publish("SLAM_POSE", garbage, sizeof(garbage));
  node.raw().publish("SLAM_POSE", garbage, 3);
  node.handle(100);
  node.handle(100);
  EXPECT_EQ(calls, 0);
  EXPECT_EQ(node.malformedCount(), 2);
  ASSERT_EQ(warnings.size(), 2u);
  EXPECT_NE(warnings[0].find("SLAM_POSE"), std::string::npos) << warnings[0];
  // A good message after the bad ones still arrives.
  slam_pose_t ok{};
  node.publish("SLAM_POSE", ok);
  node.handle(100);
  EXPECT_EQ(calls, 1);
}

// A handler that throws (a bug, or a check deeper in the process) must not end the process through LCM's C
// dispatch: the message is counted as malformed with the reason, and the next message is handled.
TEST(LcmNode, HandlerExceptionIsCountedNotFatal) {
  std::vector<std::string> warnings;
  LcmNode node("memq://", [&](const std::string& w) { warnings.push_back(w); });
  int calls = 0;
  node.subscribe<slam_pose_t>("SLAM_POSE", [&](const slam_pose_t& m, const ReceivedInfo&) {
    ++calls;
    if (m.seq < 0) throw std::runtime_error("negative seq");
  });
  node.subscribeRaw("RAW",
                    [](const void*, uint32_t, const ReceivedInfo&) { throw std::length_error("raw"); });
  slam_pose_t bad{};
  bad.seq = -1;
  node.publish("SLAM_POSE", bad);
  node.raw().publish("RAW", "x", 1);
  slam_pose_t good{};
  node.publish("SLAM_POSE", good);
  for (int i = 0; i < 3; ++i) node.handle(100);
  EXPECT_EQ(calls, 2);
  EXPECT_EQ(node.malformedCount(), 2);
  ASSERT_EQ(warnings.size(), 2u);
  EXPECT_NE(warnings[0].find("negative seq"), std::string::npos) << warnings[0];
}

// A flood of bad messages is counted in full but cannot flood the log.
TEST(LcmNode, AFloodOfMalformedMessagesIsCountedWithFewWarnings) {
  std::vector<std::string> warnings;
  LcmNode node("memq://", [&](const std::string& w) { warnings.push_back(w); });
  node.subscribe<slam_pose_t>("SLAM_POSE", [](const slam_pose_t&, const ReceivedInfo&) {});
  for (int i = 0; i < 200; ++i) {
    node.raw().publish("SLAM_POSE", "junk", 4);
    node.handle(10);
  }
  EXPECT_EQ(node.malformedCount(), 200);
  EXPECT_LE(warnings.size(), 6u);
  EXPECT_GE(warnings.size(), 5u);
}

TEST(LcmNode, BadUrlIsAClearError) {
  EXPECT_THROW(LcmNode("nonsense://x"), LcmError);
}

TEST(Conversions, ImageAndCamera) {
  EncodedImage img{2, 1, ImageEncoding::kRaw, PixelFormat::kMono16, {1, 2, 3, 4}};
  const EncodedImage back = fromMsg(toMsg(img));
  EXPECT_EQ(back.data, img.data);
  EXPECT_EQ(back.pixel_format, PixelFormat::kMono16);
  image_t bad = toMsg(img);
  bad.encoding = 9;
  EXPECT_THROW(fromMsg(bad), ImageError);
  CameraIntrinsics k;
  k.distortion = {0.1, -0.2, 0.01, 0.02, 0.3};
  const CameraIntrinsics k2 = fromMsg(toMsg(k), 1000.0);
  EXPECT_EQ(k2.distortion, k.distortion);
  EXPECT_EQ(k2.depth_scale, 1000.0);
}

}  // namespace
}  // namespace bmp

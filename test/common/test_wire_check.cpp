// The wire check must accept every valid encoding of every message type (so its layouts cannot drift from
// lcmtypes/) and refuse, without allocating, every declared length the bytes cannot back.
#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include <bmp/detections_t.hpp>
#include <bmp/keyframe_poses_t.hpp>
#include <bmp/keyframe_t.hpp>
#include <bmp/occupancy_grid_t.hpp>
#include <bmp/octomap_t.hpp>
#include <bmp/point_cloud_t.hpp>
#include <bmp/process_status_t.hpp>
#include <bmp/rgbd_frame_t.hpp>
#include <bmp/slam_pose_t.hpp>

#include "bmp/lcm/wire_check.hpp"

namespace bmp {
namespace {

template <typename Msg>
std::vector<uint8_t> encode(const Msg& msg) {
  std::vector<uint8_t> buf(static_cast<std::size_t>(msg.getEncodedSize()));
  EXPECT_EQ(msg.encode(buf.data(), 0, static_cast<int>(buf.size())), static_cast<int>(buf.size()));
  return buf;
}

image_t someImage(int32_t bytes) {
  image_t img{};
  img.width = 4;
  img.height = 2;
  img.size = bytes;
  img.data.assign(static_cast<std::size_t>(bytes), 7);
  return img;
}

rgbd_frame_t someFrame() {
  rgbd_frame_t f{};
  f.seq = 3;
  f.source = "synthetic";
  f.camera.width = 4;
  f.camera.height = 2;
  f.depth_scale = 5000;
  f.color = someImage(24);
  f.depth = someImage(16);
  return f;
}

detections_t someDetections(int n) {
  detections_t d{};
  d.model = "yolov5n";
  d.num_detections = n;
  for (int i = 0; i < n; ++i) {
    detection_t b{};
    b.label = i % 2 ? "person" : "";
    d.detections.push_back(b);
  }
  return d;
}

// Every type, with non-empty arrays and strings, passes and decodes back to the same encoding.
template <typename Msg>
void expectRoundTrip(const Msg& msg) {
  const auto buf = encode(msg);
  EXPECT_EQ(wire::check<Msg>(buf.data(), buf.size()), "") << Msg::getTypeName();
  Msg back;
  std::string why;
  ASSERT_TRUE(wire::decode(back, buf.data(), buf.size(), why)) << why;
  EXPECT_EQ(encode(back), buf);
  // Every proper prefix is truncated, and one trailing byte too many is refused.
  for (std::size_t n = 0; n < buf.size(); ++n)
    EXPECT_NE(wire::check<Msg>(buf.data(), n), "") << Msg::getTypeName() << " prefix " << n;
  auto longer = buf;
  longer.push_back(0);
  EXPECT_NE(wire::check<Msg>(longer.data(), longer.size()).find("trailing"), std::string::npos);
}

TEST(WireCheck, EveryTypeRoundTripsAndEveryPrefixIsRefused) {
  expectRoundTrip(someFrame());
  expectRoundTrip(someDetections(3));
  slam_pose_t pose{};
  pose.seq = 9;
  expectRoundTrip(pose);
  keyframe_t kf{};
  kf.color = someImage(5);
  kf.depth = someImage(6);
  kf.dynamic_mask = someImage(2);
  expectRoundTrip(kf);
  keyframe_poses_t kp{};
  kp.num_keyframes = 2;
  kp.ids = {1, 2};
  kp.T_world_cam.resize(2);
  expectRoundTrip(kp);
  occupancy_grid_t grid{};
  grid.frame_id = "world";
  grid.num_cells = 6;
  grid.cells.assign(6, -1);
  expectRoundTrip(grid);
  octomap_t oct{};
  oct.frame_id = "world";
  oct.size = 3;
  oct.data = {1, 2, 3};
  expectRoundTrip(oct);
  point_cloud_t cloud{};
  cloud.frame_id = "world";
  cloud.num_points = 2;
  cloud.points = {{1, 2, 3}, {4, 5, 6}};
  cloud.colors = {{1, 2, 3}, {4, 5, 6}};
  expectRoundTrip(cloud);
  process_status_t status{};
  status.name = "bmp-tracker";
  status.message = "ok";
  expectRoundTrip(status);
}

// Overwrites the big-endian int32 at offset.
void putInt32(std::vector<uint8_t>& buf, std::size_t offset, int32_t v) {
  const auto u = static_cast<uint32_t>(v);
  for (int i = 0; i < 4; ++i) buf[offset + i] = static_cast<uint8_t>(u >> (24 - 8 * i));
}

// Offset of the colour image's `size` field in an encoded someFrame().
std::size_t colorSizeOffset(const rgbd_frame_t& f) {
  return 8 + 3 * 8 + 4 + f.source.size() + 1 + 80 + 8 + 10;
}

TEST(WireCheck, HostileLengthsAreRefusedByName) {
  const rgbd_frame_t frame = someFrame();
  for (int32_t bad : {-1, std::numeric_limits<int32_t>::max(), std::numeric_limits<int32_t>::min(), 25}) {
    auto buf = encode(frame);
    putInt32(buf, colorSizeOffset(frame), bad);
    const std::string why = wire::check<rgbd_frame_t>(buf.data(), buf.size());
    EXPECT_NE(why.find("image_t"), std::string::npos) << bad << ": " << why;
    rgbd_frame_t out;
    std::string reason;
    EXPECT_FALSE(wire::decode(out, buf.data(), buf.size(), reason));  // and nothing was allocated
  }
  // A detections count that the bytes cannot back, negative or huge.
  const detections_t dets = someDetections(0);
  for (int32_t bad : {-1, 1000000, std::numeric_limits<int32_t>::max()}) {
    auto buf = encode(dets);
    putInt32(buf, buf.size() - 4, bad);
    EXPECT_NE(wire::check<detections_t>(buf.data(), buf.size()).find("num_detections"), std::string::npos);
  }
  // A string whose length is zero or negative (LCM's decoder would throw from std::string).
  auto buf = encode(frame);
  putInt32(buf, 8 + 3 * 8, 0);
  EXPECT_NE(wire::check<rgbd_frame_t>(buf.data(), buf.size()).find("source"), std::string::npos);
}

TEST(WireCheck, AnotherTypeOrRandomBytesAreRefused) {
  const auto pose = encode(slam_pose_t{});
  EXPECT_NE(wire::check<detections_t>(pose.data(), pose.size()).find("fingerprint"), std::string::npos);
  std::mt19937 rng(42);
  std::uniform_int_distribution<int> byte(0, 255);
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<uint8_t> junk(static_cast<std::size_t>(trial * 7));
    for (auto& b : junk) b = static_cast<uint8_t>(byte(rng));
    EXPECT_NE(wire::check<rgbd_frame_t>(junk.data(), junk.size()), "");
    // Random bytes behind the right fingerprint: refused or decoded, never a throw or a huge allocation.
    auto framed = encode(someFrame());
    for (std::size_t i = 8; i < framed.size(); ++i) framed[i] = static_cast<uint8_t>(byte(rng));
    rgbd_frame_t out;
    std::string why;
    (void)wire::decode(out, framed.data(), framed.size(), why);
    EXPECT_LE(out.color.data.size() + out.depth.data.size(), framed.size());
  }
}

}  // namespace
}  // namespace bmp

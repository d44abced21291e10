#include "bmp/lcm/wire_check.hpp"

#include <cstdint>
#include <limits>
#include <stdexcept>

#include <bmp/camera_t.hpp>
#include <bmp/detection_t.hpp>
#include <bmp/detections_t.hpp>
#include <bmp/image_t.hpp>
#include <bmp/keyframe_poses_t.hpp>
#include <bmp/keyframe_t.hpp>
#include <bmp/occupancy_grid_t.hpp>
#include <bmp/octomap_t.hpp>
#include <bmp/point_cloud_t.hpp>
#include <bmp/pose_t.hpp>
#include <bmp/process_status_t.hpp>
#include <bmp/rgbd_frame_t.hpp>
#include <bmp/slam_pose_t.hpp>

namespace bmp::wire {

namespace {

struct WireError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Walks an encoded message field by field (big-endian, as LCM writes it) without allocating.
class Reader {
 public:
  Reader(const void* data, std::size_t size) : p_(static_cast<const uint8_t*>(data)), left_(size) {}

  void skip(std::size_t n, const char* what) {
    if (n > left_)
      throw WireError(std::string(what) + " needs " + std::to_string(n) + " bytes, " + std::to_string(left_) +
                      " left (truncated)");
    p_ += n;
    left_ -= n;
  }
  int64_t int64(const char* what) {
    const uint8_t* at = p_;
    skip(8, what);
    uint64_t v = 0;
    for (int i = 0; i < 8; ++i) v = (v << 8) | at[i];
    return static_cast<int64_t>(v);
  }
  int32_t int32(const char* what) {
    const uint8_t* at = p_;
    skip(4, what);
    return static_cast<int32_t>((uint32_t{at[0]} << 24) | (uint32_t{at[1]} << 16) | (uint32_t{at[2]} << 8) |
                                uint32_t{at[3]});
  }
  // An element count: not negative, and count elements of at least min_bytes each must fit what is left.
  std::size_t count(const char* what, std::size_t min_bytes) {
    const int32_t n = int32(what);
    if (n < 0) throw WireError(std::string(what) + " = " + std::to_string(n) + " (negative)");
    if (min_bytes > 0 && static_cast<std::size_t>(n) > left_ / min_bytes)
      throw WireError(std::string(what) + " = " + std::to_string(n) + " needs at least " +
                      std::to_string(static_cast<uint64_t>(n) * min_bytes) + " bytes, " +
                      std::to_string(left_) + " left");
    return static_cast<std::size_t>(n);
  }
  // LCM strings: int32 length including the terminating NUL, then the bytes.
  void string(const char* what) {
    const int32_t n = int32(what);
    if (n < 1) throw WireError(std::string(what) + " length " + std::to_string(n) + " (must be >= 1)");
    skip(static_cast<std::size_t>(n), what);
  }
  std::size_t left() const { return left_; }

 private:
  const uint8_t* p_;
  std::size_t left_;
};

// Field layouts, in .lcm order; the byte counts are the fixed-size runs between variable fields.
void camera(Reader& r) {
  r.skip(2 * 4 + 4 * 8 + 5 * 8, "camera_t");
}
void pose(Reader& r) {
  r.skip(7 * 8, "pose_t");
}
void image(Reader& r) {
  r.skip(4 + 4 + 1 + 1, "image_t header");
  r.skip(r.count("image_t.size", 1), "image_t.data");
}
constexpr std::size_t kMinDetectionBytes = 4 * 4 + 2 + (4 + 1) + 4 + 1;
void detection(Reader& r) {
  r.skip(4 * 4 + 2, "detection_t box");
  r.string("detection_t.label");
  r.skip(4 + 1, "detection_t score");
}

void walk(Reader& r, const rgbd_frame_t*) {
  r.skip(3 * 8, "rgbd_frame_t stamps");
  r.string("rgbd_frame_t.source");
  camera(r);
  r.skip(8, "rgbd_frame_t.depth_scale");
  image(r);
  image(r);
}
void walk(Reader& r, const detections_t*) {
  r.skip(2 * 8, "detections_t stamps");
  r.string("detections_t.model");
  r.skip(4 + 4 + 4, "detections_t sizes");
  r.string("detections_t.skipped");
  const std::size_t n = r.count("detections_t.num_detections", kMinDetectionBytes);
  for (std::size_t i = 0; i < n; ++i) detection(r);
}
void walk(Reader& r, const detection_t*) {
  detection(r);
}
void walk(Reader& r, const slam_pose_t*) {
  r.skip(2 * 8, "slam_pose_t stamps");
  pose(r);
  r.skip(1 + 4 * 4 + 8 + 4 + 4, "slam_pose_t counts");
  r.string("slam_pose_t.note");
}
void walk(Reader& r, const keyframe_t*) {
  r.skip(3 * 8, "keyframe_t ids");
  pose(r);
  camera(r);
  r.skip(8, "keyframe_t.depth_scale");
  image(r);
  image(r);
  image(r);
}
void walk(Reader& r, const keyframe_poses_t*) {
  r.skip(8, "keyframe_poses_t.utime");
  const std::size_t n = r.count("keyframe_poses_t.num_keyframes", 8 + 7 * 8);
  r.skip(n * 8, "keyframe_poses_t.ids");
  for (std::size_t i = 0; i < n; ++i) pose(r);
}
void walk(Reader& r, const occupancy_grid_t*) {
  r.skip(8, "occupancy_grid_t.utime");
  r.string("occupancy_grid_t.frame_id");
  r.skip(4 + 4 + 4, "occupancy_grid_t size");
  pose(r);
  r.skip(r.count("occupancy_grid_t.num_cells", 1), "occupancy_grid_t.cells");
}
void walk(Reader& r, const octomap_t*) {
  r.skip(8, "octomap_t.utime");
  r.string("octomap_t.frame_id");
  r.skip(8 + 1, "octomap_t header");
  r.skip(r.count("octomap_t.size", 1), "octomap_t.data");
}
void walk(Reader& r, const point_cloud_t*) {
  r.skip(8, "point_cloud_t.utime");
  r.string("point_cloud_t.frame_id");
  const std::size_t n = r.count("point_cloud_t.num_points", 3 * 4 + 3);
  r.skip(n * 3 * 4, "point_cloud_t.points");
  r.skip(n * 3, "point_cloud_t.colors");
}
void walk(Reader& r, const process_status_t*) {
  r.skip(8, "process_status_t.utime");
  r.string("process_status_t.name");
  r.skip(4 + 8 + 1 + 4 + 4 + 5 * 8, "process_status_t counters");
  r.string("process_status_t.message");
}
void walk(Reader& r, const image_t*) {
  image(r);
}
void walk(Reader& r, const camera_t*) {
  camera(r);
}
void walk(Reader& r, const pose_t*) {
  pose(r);
}

template <typename Msg>
std::string checkType(const void* data, std::size_t size) {
  if (size > static_cast<std::size_t>(std::numeric_limits<int>::max())) return "larger than LCM can decode";
  try {
    Reader r(data, size);
    if (r.int64("fingerprint") != Msg::getHash())
      return std::string("fingerprint is not ") + Msg::getTypeName() +
             "'s (another type, or another version)";
    walk(r, static_cast<const Msg*>(nullptr));
    if (r.left() != 0) return std::to_string(r.left()) + " trailing bytes after " + Msg::getTypeName();
  } catch (const WireError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

#define BMP_WIRE_CHECK(T)                                    \
  template <>                                                \
  std::string check<T>(const void* data, std::size_t size) { \
    return checkType<T>(data, size);                         \
  }
BMP_WIRE_CHECK(rgbd_frame_t)
BMP_WIRE_CHECK(detections_t)
BMP_WIRE_CHECK(detection_t)
BMP_WIRE_CHECK(slam_pose_t)
BMP_WIRE_CHECK(keyframe_t)
BMP_WIRE_CHECK(keyframe_poses_t)
BMP_WIRE_CHECK(occupancy_grid_t)
BMP_WIRE_CHECK(octomap_t)
BMP_WIRE_CHECK(point_cloud_t)
BMP_WIRE_CHECK(process_status_t)
BMP_WIRE_CHECK(image_t)
BMP_WIRE_CHECK(camera_t)
BMP_WIRE_CHECK(pose_t)
#undef BMP_WIRE_CHECK

}  // namespace bmp::wire

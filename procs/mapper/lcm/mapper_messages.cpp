#include "mapper/lcm/mapper_messages.hpp"

#include "bmp/common/image_codec.hpp"
#include "bmp/common/stamp.hpp"
#include "bmp/lcm/conversions.hpp"

namespace bmp::mapper {

namespace {

const char* const kWorld = "world";

}  // namespace

std::string keyframeFromMessage(const keyframe_t& msg, KeyframeInput& out) {
  out.id = msg.id;
  out.stamp = utimeToSeconds(msg.utime);
  out.T_world_cam = fromMsg(msg.T_world_cam);
  if (std::string why = checkPoseMessage(msg.T_world_cam); !why.empty()) return why;
  out.camera = fromMsg(msg.camera, msg.depth_scale);
  const auto declared = [](const image_t& image) { return cv::Size(image.width, image.height); };
  if (std::string why = checkKeyframeHeader(out.camera, declared(msg.depth), declared(msg.color),
                                            declared(msg.dynamic_mask));
      !why.empty())
    return why;
  const auto decode = [](const image_t& image, const char* what, cv::Mat& into) -> std::string {
    try {
      into = decodeImage(fromMsg(image));
      return "";
    } catch (const ImageError& e) {
      return std::string(what) + " does not decode: " + e.what();
    }
  };
  std::string why = decode(msg.depth, "depth", out.depth);
  if (why.empty()) why = decode(msg.color, "colour", out.color);
  if (why.empty()) why = decode(msg.dynamic_mask, "mask", out.dynamic_mask);
  if (why.empty()) why = checkKeyframe(out);
  return why;
}

std::vector<PoseUpdate> poseUpdatesFromMessage(const keyframe_poses_t& msg,
                                               std::vector<std::string>& rejected) {
  std::vector<PoseUpdate> out;
  // The wire check guarantees both arrays hold num_keyframes entries.
  for (std::size_t i = 0; i < msg.ids.size() && i < msg.T_world_cam.size(); ++i) {
    const std::string why = checkPoseMessage(msg.T_world_cam[i]);
    if (why.empty())
      out.push_back({msg.ids[i], fromMsg(msg.T_world_cam[i])});
    else
      rejected.push_back("keyframe " + std::to_string(msg.ids[i]) + ": " + why);
  }
  return out;
}

occupancy_grid_t toGridMessage(const OccupancyGrid2D& grid, int64_t utime) {
  occupancy_grid_t msg;
  msg.utime = utime;
  msg.frame_id = kWorld;
  msg.resolution = static_cast<float>(grid.resolution);
  msg.width = grid.width;
  msg.height = grid.height;
  msg.origin = toMsg(grid.T_world_origin());
  msg.num_cells = static_cast<int32_t>(grid.cells.size());
  msg.cells = grid.cells;
  return msg;
}

octomap_t toOctomapMessage(const OccupancyMap& map, int64_t utime) {
  octomap_t msg;
  msg.utime = utime;
  msg.frame_id = kWorld;
  msg.resolution = map.resolution();
  msg.binary = true;
  const std::string data = map.binaryData();
  msg.size = static_cast<int32_t>(data.size());
  msg.data.assign(data.begin(), data.end());
  return msg;
}

point_cloud_t toCloudMessage(const PointList& cloud, int64_t utime, std::size_t max_points) {
  point_cloud_t msg;
  msg.utime = utime;
  msg.frame_id = kWorld;
  const double step = cloud.size() > max_points ? static_cast<double>(cloud.size()) / max_points : 1.0;
  for (double i = 0; i < static_cast<double>(cloud.size()); i += step) {
    const ColoredPoint& p = cloud[static_cast<std::size_t>(i)];
    msg.points.push_back({p.x, p.y, p.z});
    msg.colors.push_back({p.r, p.g, p.b});
  }
  msg.num_points = static_cast<int32_t>(msg.points.size());
  return msg;
}

}  // namespace bmp::mapper

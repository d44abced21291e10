#pragma once
// Between the mapper's LCM messages and the library's types. Every message is untrusted: the wire format
// was checked by LcmNode, the content is checked here and by checkKeyframe.
#include <cstdint>
#include <string>
#include <vector>

#include <bmp/keyframe_poses_t.hpp>
#include <bmp/keyframe_t.hpp>
#include <bmp/occupancy_grid_t.hpp>
#include <bmp/octomap_t.hpp>
#include <bmp/point_cloud_t.hpp>

#include "mapper/mapper.hpp"

namespace bmp::mapper {

// Decodes the images and fills out; returns why the keyframe cannot be used ("" when it can): an image
// that does not decode, or anything checkKeyframe refuses.
std::string keyframeFromMessage(const keyframe_t& msg, KeyframeInput& out);
// The updates whose poses are usable; the others go to rejected, one line each naming the keyframe id.
std::vector<PoseUpdate> poseUpdatesFromMessage(const keyframe_poses_t& msg,
                                               std::vector<std::string>& rejected);

occupancy_grid_t toGridMessage(const OccupancyGrid2D& grid, int64_t utime);
octomap_t toOctomapMessage(const OccupancyMap& map, int64_t utime);
// At most max_points (evenly thinned beyond that).
point_cloud_t toCloudMessage(const PointList& cloud, int64_t utime, std::size_t max_points);

}  // namespace bmp::mapper

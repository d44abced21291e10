#pragma once
// The channel names of the message flow (../shared/DESIGN.md), defined once. Configuration may rename a
// channel; these are the defaults every process, tool and test starts from.
namespace bmp::channels {

inline constexpr const char* kFrames = "RGBD_FRAME";                  // rgbd_frame_t, bmp-capture
inline constexpr const char* kDetections = "DETECTIONS";              // detections_t, bmp-detector
inline constexpr const char* kPose = "SLAM_POSE";                     // slam_pose_t, bmp-tracker
inline constexpr const char* kKeyframe = "SLAM_KEYFRAME";             // keyframe_t, bmp-tracker
inline constexpr const char* kKeyframePoses = "SLAM_KEYFRAME_POSES";  // keyframe_poses_t, bmp-tracker
inline constexpr const char* kOctomap = "OCTOMAP";                    // octomap_t, bmp-mapper
inline constexpr const char* kOccupancyGrid = "OCCUPANCY_GRID";       // occupancy_grid_t, bmp-mapper
inline constexpr const char* kMapCloud = "MAP_CLOUD";                 // point_cloud_t, bmp-mapper
inline constexpr const char* kProcessStatus = "PROCESS_STATUS";       // process_status_t, every process

}  // namespace bmp::channels

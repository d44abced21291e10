#pragma once
// bmp-mapper's process side (the `process` section of config/mapper.yaml): channels, publishing and saving
// rates. Read and checked here, once.
#include <string>

#include "bmp/common/config.hpp"
#include "bmp/lcm/channels.hpp"

namespace bmp::mapper {

struct MapperProcessSettings {
  std::string keyframe_channel = channels::kKeyframe;
  std::string keyframe_poses_channel = channels::kKeyframePoses;
  std::string octomap_channel = channels::kOctomap;
  std::string grid_channel = channels::kOccupancyGrid;
  std::string cloud_channel = channels::kMapCloud;
  double grid_period_s = 1.0;     // OCCUPANCY_GRID and OCTOMAP, when the map changed
  double grid_repeat_s = 5.0;     // ... and this often even when it did not (LCM keeps no last message)
  double cloud_period_s = 2.0;    // MAP_CLOUD, when the map changed
  double save_period_s = 60.0;    // map files; 0: only on exit and SIGUSR1
  int max_cloud_points = 200000;  // MAP_CLOUD is thinned to this many points (LCM messages stay < 4 MiB)
  // Keyframes integrated with one camera before it is kept for the run; until then a keyframe of another
  // camera replaces it and the map starts again (a forged keyframe before the tracker's first must not lock
  // the real camera out). Once kept, another camera's keyframes are refused before they are decoded.
  int camera_settle_keyframes = 3;
  // Keyframes and pose updates waiting for the loop (mapper_inbox.hpp), in MiB: about 45 VGA keyframes.
  double inbox_mib = 64.0;
  // At a stop, messages still in the inbox are mapped for at most this long, then the map is saved (the
  // launcher kills a process that takes more than its stop_timeout_s, 15 s, to stop).
  double stop_drain_s = 5.0;
};

MapperProcessSettings processSettingsFromConfig(const Config& section);

}  // namespace bmp::mapper

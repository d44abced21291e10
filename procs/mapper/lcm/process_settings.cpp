#include "mapper/lcm/process_settings.hpp"

#include <cmath>

namespace bmp::mapper {

MapperProcessSettings processSettingsFromConfig(const Config& c) {
  MapperProcessSettings s;
  s.keyframe_channel = c.get<std::string>("keyframe_channel", s.keyframe_channel);
  s.keyframe_poses_channel = c.get<std::string>("keyframe_poses_channel", s.keyframe_poses_channel);
  s.octomap_channel = c.get<std::string>("octomap_channel", s.octomap_channel);
  s.grid_channel = c.get<std::string>("grid_channel", s.grid_channel);
  s.cloud_channel = c.get<std::string>("cloud_channel", s.cloud_channel);
  s.grid_period_s = c.get<double>("grid_period_s", s.grid_period_s);
  s.grid_repeat_s = c.get<double>("grid_repeat_s", s.grid_repeat_s);
  s.cloud_period_s = c.get<double>("cloud_period_s", s.cloud_period_s);
  s.save_period_s = c.get<double>("save_period_s", s.save_period_s);
  s.max_cloud_points = c.get<int>("max_cloud_points", s.max_cloud_points);
  s.camera_settle_keyframes = c.get<int>("camera_settle_keyframes", s.camera_settle_keyframes);
  s.inbox_mib = c.get<double>("inbox_mib", s.inbox_mib);
  s.stop_drain_s = c.get<double>("stop_drain_s", s.stop_drain_s);
  for (const char* key :
       {"keyframe_channel", "keyframe_poses_channel", "octomap_channel", "grid_channel", "cloud_channel"})
    c.check(!c.get<std::string>(key, "x").empty(), key, "must not be empty");
  c.check(std::isfinite(s.grid_period_s) && s.grid_period_s > 0, "grid_period_s", "must be positive");
  c.check(std::isfinite(s.grid_repeat_s) && s.grid_repeat_s >= s.grid_period_s, "grid_repeat_s",
          "must be at least grid_period_s");
  c.check(std::isfinite(s.cloud_period_s) && s.cloud_period_s > 0, "cloud_period_s", "must be positive");
  c.check(std::isfinite(s.save_period_s) && s.save_period_s >= 0, "save_period_s", "must not be negative");
  c.check(s.max_cloud_points >= 1000 && s.max_cloud_points <= 250000, "max_cloud_points",
          "must be in 1000..250000 (a MAP_CLOUD message must stay under 4 MiB)");
  c.check(s.camera_settle_keyframes >= 1, "camera_settle_keyframes", "must be at least 1");
  c.check(std::isfinite(s.inbox_mib) && s.inbox_mib >= 1 && s.inbox_mib <= 16384, "inbox_mib",
          "must be in 1..16384");
  c.check(std::isfinite(s.stop_drain_s) && s.stop_drain_s >= 0, "stop_drain_s", "must not be negative");
  return s;
}

}  // namespace bmp::mapper

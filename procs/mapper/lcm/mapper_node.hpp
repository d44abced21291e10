#pragma once
// bmp-mapper's LCM side: keyframes and pose updates in (a receive thread puts them in the inbox), the
// library's Mapper called on each in the loop, the grid, the octree and a viewer cloud out at their rates,
// map files on SIGUSR1, at an interval and at exit.
#include <atomic>
#include <optional>
#include <string>
#include <thread>

#include <bmp/keyframe_poses_t.hpp>
#include <bmp/keyframe_t.hpp>

#include "bmp/common/timing.hpp"
#include "bmp/common/warning_throttle.hpp"
#include "bmp/lcm/camera_pin.hpp"
#include "bmp/lcm/process.hpp"
#include "mapper/lcm/mapper_inbox.hpp"
#include "mapper/lcm/process_settings.hpp"
#include "mapper/lcm/save_signal.hpp"
#include "mapper/mapper.hpp"
#include "mapper/pose_update_order.hpp"

namespace bmp::mapper {

class MapperNode {
 public:
  // Subscribes and starts receiving at once. SIGUSR1 is blocked from here on and read in run().
  MapperNode(ProcessContext& ctx, const MapperSettings& settings, MapperProcessSettings process,
             std::string out_dir);
  ~MapperNode();  // stops the receive thread
  MapperNode(const MapperNode&) = delete;
  MapperNode& operator=(const MapperNode&) = delete;

  // Until a stop is requested; then what waits in the inbox is mapped too.
  void run();
  // Writes every map file into the output folder; returns false when it could not. A failure is logged,
  // never fatal here (the map lives on); the last save decides the exit status.
  bool save(const std::string& why);
  // The save at exit. A run that mapped nothing leaves a map already in the folder as it was: a mapper
  // restarted on yesterday's folder and stopped before any keyframe came must not replace it with nothing.
  bool saveAtExit();

 private:
  void receive();  // the receive thread's loop
  void stopReceiving();
  void dispatch(const MapperInbox::Message& message);
  void reportRefusedByInbox();
  void onKeyframe(const keyframe_t& msg);
  void onPoses(const keyframe_poses_t& msg);
  // The keyframe's camera becomes the map's: the first, or one replacing an unsettled camera (the map
  // made with that one is dropped). Another camera after it settled is refused before decoding.
  void startMapWithCamera(const keyframe_t& msg);
  // Keyframe 0 again, at the origin, with the map's camera: the tracker began a new map (it was restarted),
  // whose world frame is not this map's. The map so far is saved into its own folder and a new one starts;
  // merged, the new map's keyframes would land in the old one's frame.
  bool startsNewTrackerMap(const keyframe_t& msg) const;
  void setAsideForNewTrackerMap();
  // An empty map in place of the one held: no keyframes, no pose stamps, no fitted floor.
  void startEmptyMap();
  void publishDue(double now_s);
  // The loop's work besides messages: octree upkeep, publishing, saving.
  void maintainAndPublish(double now_s);
  void reportFloor();  // logs when the floor is first fitted
  void refuse(const std::string& what);
  std::string statusLine() const;

  ProcessContext& ctx_;
  MapperProcessSettings process_;
  std::string out_dir_;
  std::optional<Mapper> mapper_;  // made again when another camera replaces an unsettled one
  CameraPin camera_;
  PoseUpdateOrder pose_order_;  // older pose updates than a keyframe has are refused
  SaveSignal save_signal_;
  Stopwatch clock_;
  double last_grid_s_ = -1e300, last_cloud_s_ = -1e300, last_save_s_ = 0, last_status_s_ = -1e300;
  bool grid_dirty_ = false, cloud_dirty_ = false, save_dirty_ = false, status_dirty_ = false;
  std::string last_warning_;
  WarningThrottle warnings_;  // a flood of bad input (16k pose updates in one message) cannot flood the log
  std::optional<FloorPlane> floor_reported_;  // the floor last logged
  std::optional<std::size_t> saved_points_;   // points in the files of the last save
  int maps_set_aside_ = 0;                    // earlier tracker maps saved into out/tracker_map_<n>/
  MapperInbox inbox_;
  int64_t inbox_refusals_reported_ = 0;
  std::atomic<bool> receiving_{true};
  std::thread receiver_;  // last: started once everything it uses exists
};

}  // namespace bmp::mapper

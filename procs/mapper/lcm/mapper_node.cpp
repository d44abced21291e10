#include "mapper/lcm/mapper_node.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "bmp/common/atomic_file.hpp"
#include "bmp/common/log.hpp"
#include "bmp/common/memory_usage.hpp"
#include "bmp/lcm/conversions.hpp"
#include "mapper/lcm/mapper_messages.hpp"
#include "mapper/map_files.hpp"

namespace bmp::mapper {

namespace {
constexpr double kStatusLineS = 0.25;
constexpr double kFloorReportDeg = 1.0;  // a refit this far from the floor last logged is logged
constexpr double kFloorReportM = 0.03;   // ... or this far along its normal
}  // namespace

MapperNode::MapperNode(ProcessContext& ctx, const MapperSettings& settings, MapperProcessSettings process,
                       std::string out_dir)
    : ctx_(ctx),
      process_(std::move(process)),
      out_dir_(std::move(out_dir)),
      mapper_(std::in_place, settings),
      camera_(process_.camera_settle_keyframes),
      inbox_(static_cast<std::size_t>(process_.inbox_mib * (1 << 20))) {
  ctx_.lcm.subscribe<keyframe_t>(process_.keyframe_channel,
                                 [this](const keyframe_t& m, const ReceivedInfo&) { inbox_.offer(m); });
  ctx_.lcm.subscribe<keyframe_poses_t>(
      process_.keyframe_poses_channel,
      [this](const keyframe_poses_t& m, const ReceivedInfo&) { inbox_.offer(m); });
  receiver_ = std::thread([this] { receive(); });
}

MapperNode::~MapperNode() {
  stopReceiving();
}

void MapperNode::receive() {
  while (receiving_ && !ctx_.stop.requested()) {
    if (!ctx_.lcm.handle(100)) {
      log::error("LCM receive failed; stopping");
      ctx_.stop.request();
    }
  }
}

void MapperNode::stopReceiving() {
  receiving_ = false;
  if (receiver_.joinable()) receiver_.join();
  inbox_.close();
}

void MapperNode::dispatch(const MapperInbox::Message& message) {
  // As LCM's handler did before the inbox: whatever one message leads to (a keyframe too large to allocate)
  // is that message's refusal, never the mapper's end.
  const auto* kf = std::get_if<keyframe_t>(&message);
  try {
    if (kf != nullptr)
      onKeyframe(*kf);
    else
      onPoses(std::get<keyframe_poses_t>(message));
  } catch (const std::exception& e) {
    refuse((kf != nullptr ? "keyframe " + std::to_string(kf->id) : std::string("pose update")) + ": " +
           e.what() + "; skipped");
  }
}

void MapperNode::reportRefusedByInbox() {
  const int64_t refused = inbox_.refusedCount();
  if (refused == inbox_refusals_reported_) return;
  const int64_t more = refused - inbox_refusals_reported_;
  inbox_refusals_reported_ = refused;
  ctx_.status.received(more);
  ctx_.status.dropped(more);
  status_dirty_ = true;
  last_warning_ =
      std::to_string(refused) + " message(s) dropped: the mapper fell behind by process.inbox_mib";
  if (const auto left_out = warnings_.admit("inbox full"))
    log::warn(more, " keyframe or pose message(s) dropped: ", static_cast<int>(process_.inbox_mib),
              " MiB of them already waited for the mapper (process.inbox_mib), ", refused, " in all",
              leftOutNote(*left_out));
}

void MapperNode::run() {
  while (!ctx_.stop.requested()) {
    if (const auto message = inbox_.popFor(std::chrono::milliseconds(100))) dispatch(*message);
    reportRefusedByInbox();
    const double now = clock_.elapsedMs() * 1e-3;
    try {
      maintainAndPublish(now);
    } catch (const std::exception& e) {
      // Whatever a message led to (a grid too large to allocate or to send): reported, and the mapper goes
      // on mapping; what it holds is saved at exit all the same.
      const std::string what = std::string("map upkeep failed: ") + e.what();
      if (what != last_warning_) {  // counted and logged once, not every turn of the loop
        log::error(what);
        ctx_.status.malformed();
      }
      last_warning_ = what;
      status_dirty_ = true;
    }
    // Reads /proc and takes medians over every keyframe so far: at most every kStatusLineS after a message
    // (a flood of revisits made one per message cost 120 ms at a million), once a second otherwise.
    if ((status_dirty_ && now - last_status_s_ >= kStatusLineS) || now - last_status_s_ >= 1.0) {
      last_status_s_ = now;
      status_dirty_ = false;
      ctx_.status.setMessage(statusLine());
    }
    ctx_.status.tick();
  }
  // What came before the stop is mapped before the map is saved, for at most process.stop_drain_s: the
  // launcher kills a process that takes too long to stop, and the map would be lost with it.
  stopReceiving();
  const Stopwatch draining;
  std::size_t late = 0, left = 0;
  for (auto message = inbox_.tryPop(); message; message = inbox_.tryPop()) {
    if (draining.elapsedMs() < process_.stop_drain_s * 1000.0) {
      dispatch(*message);
      ++late;
    } else {
      ++left;
    }
  }
  if (late > 0) log::info(late, " message(s) that waited at the stop mapped");
  if (left > 0) {
    log::warn(left, " message(s) that waited at the stop not mapped: process.stop_drain_s (",
              process_.stop_drain_s, " s) passed");
    ctx_.status.received(static_cast<int64_t>(left));
    ctx_.status.dropped(static_cast<int64_t>(left));
  }
  reportRefusedByInbox();
  log::info("mapped ", mapper_->keyframeCount(), " keyframes (+", mapper_->mergedCount(),
            " revisits merged); integration ", mapper_->integrationTimes().summary());
}

void MapperNode::maintainAndPublish(double now) {
  if (mapper_->maintain(now)) {
    log::info("octree rebuilt after a pose update, beside integration: ", mapper_->keyframeCount(),
              " keyframes, ", static_cast<int>(mapper_->lastRebuildMs()), " ms");
    grid_dirty_ = true;
  }
  publishDue(now);
  if (save_signal_.pending()) save("SIGUSR1");
  if (save_dirty_ && process_.save_period_s > 0 && now - last_save_s_ >= process_.save_period_s) {
    last_save_s_ = now;
    save("periodic");
  }
}

void MapperNode::refuse(const std::string& what) {
  ctx_.status.malformed();
  last_warning_ = what;
  if (const auto left_out = warnings_.admit("refused input")) log::warn(what, leftOutNote(*left_out));
}

void MapperNode::startMapWithCamera(const keyframe_t& msg) {
  if (camera_.camera() != nullptr) {
    log::warn("keyframe ", msg.id, ": ", camera_.replacement(msg.camera, msg.depth_scale), "; dropping the ",
              mapper_->keyframeCount(), " keyframe(s) mapped with the replaced camera");
    startEmptyMap();
  }
  camera_.pin(msg.camera, msg.depth_scale);
}

bool MapperNode::startsNewTrackerMap(const keyframe_t& msg) const {
  // The tracker's first keyframe is its world's origin by definition: exactly the identity.
  const SE3 pose = fromMsg(msg.T_world_cam);
  return msg.id == 0 && mapper_->keyframeCount() > 0 && pose.translation().isZero(0.0) &&
         pose.linear().isIdentity(1e-12);
}

void MapperNode::setAsideForNewTrackerMap() {
  // The next number not on disk: a restarted mapper writing into the same folder keeps an earlier run's.
  std::filesystem::path path;
  std::error_code ec;
  do {
    path = std::filesystem::path(out_dir_) / ("tracker_map_" + std::to_string(++maps_set_aside_));
  } while (std::filesystem::exists(path, ec));
  const std::string dir = path.string();
  log::warn("keyframe 0 again, at the origin: the tracker began a new map (restarted); the map so far (",
            mapper_->keyframeCount(), " keyframes) is saved in ", dir, " and a new one starts");
  try {
    const auto written = writeMapFiles(dir, *mapper_);
    log::info("map saved (the tracker's earlier map): ", written.size(), " files in ", dir);
  } catch (const FileWriteError& e) {
    log::error("the tracker's earlier map not saved: ", e.what());
  }
  startEmptyMap();
  grid_dirty_ = cloud_dirty_ = save_dirty_ = true;
}

void MapperNode::startEmptyMap() {
  const MapperSettings settings = mapper_->settings();  // copied: emplace destroys the old mapper first
  mapper_.emplace(settings);
  pose_order_.clear();
  floor_reported_.reset();
}

void MapperNode::onKeyframe(const keyframe_t& msg) {
  ctx_.status.received();
  status_dirty_ = true;
  const CameraPin::Fit fit = camera_.fit(msg.camera, msg.depth_scale);
  KeyframeInput kf;
  std::string why = fit == CameraPin::Fit::kRefused ? camera_.refusal(msg.camera, msg.depth_scale)
                                                    : keyframeFromMessage(msg, kf);
  if (why.empty() && fit == CameraPin::Fit::kSame && startsNewTrackerMap(msg)) setAsideForNewTrackerMap();
  // A keyframe the new map would refuse must not drop the map it would replace.
  if (why.empty() && fit != CameraPin::Fit::kSame) why = mapper_->refusalOfFirst(kf);
  if (why.empty() && fit != CameraPin::Fit::kSame) startMapWithCamera(msg);
  if (why.empty()) why = mapper_->integrate(kf).reason;
  if (!why.empty()) return refuse("keyframe " + std::to_string(msg.id) + ": " + why + "; skipped");
  pose_order_.keyframeMapped(msg.utime);
  camera_.used();
  ctx_.status.processed();
  grid_dirty_ = cloud_dirty_ = save_dirty_ = true;
}

void MapperNode::onPoses(const keyframe_poses_t& msg) {
  ctx_.status.received();
  status_dirty_ = true;
  std::vector<std::string> rejected;
  const std::vector<PoseUpdate> updates =
      pose_order_.notOlder(poseUpdatesFromMessage(msg, rejected), msg.utime, rejected);
  const PoseUpdateResult r = mapper_->updatePoses(updates);
  // Only what was applied: a refused update's stamp would make a later real one look older. Bounded by the
  // map's keyframes and merged revisits.
  for (const int64_t id : r.applied_ids) pose_order_.taken(id, msg.utime);
  rejected.insert(rejected.end(), r.rejected.begin(), r.rejected.end());
  for (const auto& line : rejected) refuse("pose update for " + line + "; skipped");
  if (r.applied > 0) {
    ctx_.status.processed();
    cloud_dirty_ = save_dirty_ = true;
  }
}

void MapperNode::publishDue(double now) {
  const int64_t utime = nowUtime();
  const bool repeat = mapper_->keyframeCount() > 0 && now - last_grid_s_ >= process_.grid_repeat_s;
  if ((grid_dirty_ && now - last_grid_s_ >= process_.grid_period_s) || repeat) {
    last_grid_s_ = now;
    grid_dirty_ = false;
    ctx_.lcm.publish(process_.grid_channel, toGridMessage(mapper_->grid(), utime));
    reportFloor();
    ctx_.lcm.publish(process_.octomap_channel, toOctomapMessage(mapper_->occupancy(), utime));
    ctx_.status.published(2);
  }
  if (cloud_dirty_ && now - last_cloud_s_ >= process_.cloud_period_s) {
    last_cloud_s_ = now;
    cloud_dirty_ = false;
    const auto max_points = static_cast<std::size_t>(process_.max_cloud_points);
    ctx_.lcm.publish(process_.cloud_channel, toCloudMessage(mapper_->viewerCloud(), utime, max_points));
    ctx_.status.published();
  }
}

void MapperNode::reportFloor() {
  const auto& floor = mapper_->floor();
  if (!floor) return;  // a fitted floor stays fitted (Mapper::floor)
  // Refits are logged too once they move the floor (kFloorReportDeg, kFloorReportM): the saved grid stands
  // on the last, and a user reading only the first missed a grid 13 degrees off.
  const auto angle = [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    return std::acos(std::clamp(a.dot(b), -1.0, 1.0)) * 180.0 / M_PI;
  };
  if (floor_reported_ && angle(floor_reported_->normal, floor->normal) < kFloorReportDeg &&
      std::abs(floor_reported_->height - floor->height) < kFloorReportM)
    return;
  const char* what = floor_reported_ ? "floor refitted: " : "floor fitted: ";
  floor_reported_ = floor;
  const auto& up = mapper_->settings().grid.up;
  log::info(what, floor->height, " m along its normal, ",
            angle(floor->normal, Eigen::Vector3d(up[0], up[1], up[2]).normalized()), " deg from grid.up, ",
            static_cast<int>(100 * floor->share), " % of the points");
}

bool MapperNode::save(const std::string& why) {
  try {
    Stopwatch watch;
    const auto written = writeMapFiles(out_dir_, *mapper_);
    save_dirty_ = false;
    saved_points_ = mapper_->cloud().size();
    log::info("map saved (", why, "): ", written.size(), " files in ", out_dir_, ", ", *saved_points_,
              " points, ", static_cast<int>(watch.elapsedMs()), " ms");
    ctx_.status.setMessage(statusLine());  // the next heartbeat, the last one at exit, says what was saved
    return true;
  } catch (const FileWriteError& e) {
    log::error("map not saved (", why, "): ", e.what());
    return false;
  }
}

bool MapperNode::saveAtExit() {
  if (mapper_->keyframeCount() == 0 && !saved_points_ &&
      std::filesystem::exists(std::filesystem::path(out_dir_) / "map.pcd")) {
    log::warn("no keyframe mapped in this run: the map already in ", out_dir_, " is left as it was");
    return true;
  }
  return save("exit");
}

std::string MapperNode::statusLine() const {
  const TimingStats& t = mapper_->integrationTimes();
  // The working cloud still holds points the voxel filter and carving drop before a save: the saved figure
  // is the one to compare with the files.
  char points[96];
  if (saved_points_)
    std::snprintf(points, sizeof(points), "points %zu saved (%zu in the working cloud)", *saved_points_,
                  mapper_->pointCount());
  else
    std::snprintf(points, sizeof(points), "points none saved yet (%zu in the working cloud)",
                  mapper_->pointCount());
  char line[320];
  std::snprintf(line, sizeof(line),
                "keyframes %zu (+%zu merged), %s, octree nodes %zu, rss %.0f MiB, integration median %.1f ms",
                mapper_->keyframeCount(), mapper_->mergedCount(), points, mapper_->occupancy().nodeCount(),
                static_cast<double>(bmp::residentBytes()) / (1 << 20), t.empty() ? 0.0 : t.median());
  return last_warning_.empty() ? line : std::string(line) + "; last warning: " + last_warning_;
}

}  // namespace bmp::mapper

#include "tracker_offline/offline_runner.hpp"

#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>

#include <opencv2/imgcodecs.hpp>

#include "capture/tum_sequence.hpp"

namespace bmp::tracker {

OfflineResult runOffline(Tracker& tracker, const FrameProvider& next, const OfflineOptions& options) {
  OfflineResult out;
  int64_t seq = 0;
  while (options.max_frames < 0 || out.frames < options.max_frames) {
    auto frame = next();
    if (!frame) break;
    TrackerInput input;
    input.stamp = frame->stamp;
    input.seq = seq++;
    input.image = frame->image;
    input.depth = frame->depth;
    if (options.exclude_movers) input.exclusion_mask = frame->mover_mask;
    input.boxes = frame->boxes;
    input.boxes_stand_in = frame->boxes_stand_in;
    if (frame->late && input.seq >= frame->late->frames_back)
      tracker.applyLateBoxes(input.seq - frame->late->frames_back, frame->late->boxes);
    TrackResult r = tracker.track(input);
    out.track_ms.add(r.processing_ms);
    out.frames_lost += r.state == TrackingState::kLost;
    out.lost_at_end = r.state == TrackingState::kLost;
    out.gap_rechecks += r.gap_recheck != GapRecheck::kNone;
    out.gap_reference_taken += r.gap_recheck == GapRecheck::kReferenceTaken;
    ++out.frames;
    if (options.on_result) options.on_result(r, *frame);
    if (options.keep_results) out.results.push_back(std::move(r));
  }
  tracker.finish();
  out.trajectory = tracker.trajectory();
  out.keyframe_trajectory = tracker.keyFrameTrajectory();
  return out;
}

FrameProvider tumFolderFrames(const std::string& dir, int start, Trajectory* groundtruth, bool load_masks) {
  auto index = std::make_shared<capture::SequenceIndex>(capture::indexSequence(dir));
  if (groundtruth) *groundtruth = index->groundtruth;
  for (const auto& path : index->missing_files)
    std::fprintf(stderr, "warning: %s: listed but does not exist; skipped\n", path.c_str());
  if (!index->groundtruth_problem.empty())
    std::fprintf(stderr, "warning: %s; no ground truth\n", index->groundtruth_problem.c_str());
  for (const auto& problem : index->list_problems) std::fprintf(stderr, "warning: %s\n", problem.c_str());
  auto position = std::make_shared<std::size_t>(static_cast<std::size_t>(std::max(0, start)));
  return [index, position, load_masks]() -> std::optional<OfflineFrame> {
    while (*position < index->frames.size()) {
      const auto& pair = index->frames[(*position)++];
      OfflineFrame f;
      f.stamp = pair.rgb_stamp;
      f.image = cv::imread(pair.rgb_path, cv::IMREAD_COLOR);
      f.depth = cv::imread(pair.depth_path, cv::IMREAD_UNCHANGED);
      // The tracker process's rule (tracker_node.cpp): depth is 16-bit at the colour image's size. Named, so
      // a benchmark's frame count can be matched with the files behind it.
      const std::string why =
          f.image.empty()                    ? pair.rgb_path + ": cannot be read as an image"
          : f.depth.empty()                  ? pair.depth_path + ": cannot be read as an image"
          : f.depth.type() != CV_16UC1       ? pair.depth_path + ": not 16-bit single-channel depth"
          : f.depth.size() != f.image.size() ? pair.depth_path + ": not the colour image's size"
                                             : std::string();
      if (!why.empty()) {
        std::fprintf(stderr, "warning: frame %.6f skipped: %s\n", pair.rgb_stamp, why.c_str());
        continue;
      }
      if (load_masks) {
        const auto mask =
            std::filesystem::path(index->dir) / "mask" / std::filesystem::path(pair.rgb_path).filename();
        f.mover_mask = cv::imread(mask.string(), cv::IMREAD_GRAYSCALE);
        if (f.mover_mask.size() != f.image.size())
          throw std::runtime_error(mask.string() + ": missing, unreadable or not the size of " +
                                   pair.rgb_path);
      }
      return f;
    }
    return std::nullopt;
  };
}

}  // namespace bmp::tracker

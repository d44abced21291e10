#include "tracker_offline/offline_runner.hpp"

#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>

#include <opencv2/imgcodecs.hpp>

#include "bmp/common/image_codec.hpp"
#include "capture/tum_sequence.hpp"
#include "capture/tum_source.hpp"

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

FrameProvider tumFolderFrames(const std::string& dir, const CameraIntrinsics& camera,
                              const TumFolderOptions& folder) {
  capture::SequenceIndex index = capture::indexSequence(dir);
  if (folder.groundtruth) *folder.groundtruth = index.groundtruth;
  const auto say = [warn = folder.warn](const std::string& line) {
    if (warn) std::fprintf(stderr, "warning: %s\n", line.c_str());
  };
  if (!index.groundtruth_problem.empty()) say(index.groundtruth_problem + "; no ground truth");
  for (const auto& problem : index.list_problems) say(problem);
  // bmp-capture's reader, so a benchmark plays the frames the pipeline would: the same checks of each file
  // (missing, corrupt, not the camera's size or format), each skip named.
  capture::TumSourceOptions options;
  options.selection.start = std::max(0, folder.start);
  options.warn = say;
  auto source = std::make_shared<capture::TumSource>(std::move(index), camera, std::move(options));
  return [source, load_masks = folder.load_masks, say]() -> std::optional<OfflineFrame> {
    while (auto captured = source->next()) {
      OfflineFrame f;
      f.stamp = captured->stamp;
      try {
        f.image = decodeImage(captured->color);
        f.depth = decodeImage(captured->depth);
      } catch (const ImageError& e) {
        say("skipped frame " + std::to_string(captured->stamp) + ": " + e.what());
        continue;
      }
      if (load_masks) {
        const auto& pair = source->index().frames[static_cast<std::size_t>(captured->index)];
        const auto mask = std::filesystem::path(source->index().dir) / "mask" /
                          std::filesystem::path(pair.rgb_path).filename();
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

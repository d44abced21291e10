#include "capture/lcm/capture_node.hpp"

#include <algorithm>
#include <optional>

#include "bmp/common/log.hpp"
#include "bmp/common/tum_trajectory.hpp"
#include "bmp/lcm/wait_for_processes.hpp"
#include "capture/looped_source.hpp"
#include "capture/open_source.hpp"
#include "capture/tum_source.hpp"

namespace bmp::capture {

namespace {

// The period of one pass over a TUM folder's selected frames, known before any is read, so the looped
// ground truth can be written before the first frame.
double tumPeriod(const SequenceIndex& index, const FrameSelection& selection) {
  const auto total = static_cast<int64_t>(index.frames.size());
  const int64_t end = selectedEnd(selection, total);
  if (end <= selection.start) return 1.0;
  const int64_t last = selection.start + (end - 1 - selection.start) / selection.every * selection.every;
  const int64_t count = selectedCount(selection, total);
  return loopPeriod(index.frames[static_cast<std::size_t>(selection.start)].rgb_stamp,
                    index.frames[static_cast<std::size_t>(last)].rgb_stamp, count);
}

}  // namespace

CaptureNode::CaptureNode(ProcessContext& ctx, CaptureSettings settings)
    : ctx_(ctx),
      settings_(std::move(settings)),
      source_(openFrameSource(settings_, [this](const std::string& m) { warnSkip(m); })) {
  if (const auto* tum = dynamic_cast<const TumSource*>(source_.get())) {
    from_dataset_ = true;
    dataset_truth_ = tum->index().groundtruth;
    loop_period_s_ = tumPeriod(tum->index(), settings_.selection);
    const int64_t frames =
        selectedCount(settings_.selection, static_cast<int64_t>(tum->index().frames.size()));
    if (frames > 0) {
      pass_first_s_ = tum->index().frames[static_cast<std::size_t>(settings_.selection.start)].rgb_stamp;
      frame_s_ = loop_period_s_ / static_cast<double>(frames);
    }
  }
  if (settings_.loops > 1) {
    source_ = std::make_unique<LoopedSource>(
        std::move(source_),
        [this] {
          writeTruthPass(++truth_pass_);
          return openFrameSource(settings_, [this](const std::string& m) { warnSkip(m); });
        },
        settings_.loops, loop_period_s_);
    log::info("playing the source ", settings_.loops, " times as one stream",
              loop_period_s_ > 0 ? ", stamps offset " + std::to_string(loop_period_s_) + " s per pass" : "");
  }
}

void CaptureNode::writeTruthPass(int pass) {
  if (!dataset_truth_out_) return;
  const double shift = loop_period_s_ * pass;
  const double from = pass_first_s_ - 0.5 * frame_s_, to = from + loop_period_s_;
  for (const auto& p : dataset_truth_)
    if (settings_.loops == 1 || (p.stamp >= from && p.stamp < to)) {
      dataset_truth_out_->append({p.stamp + shift, p.T_world_cam});
      ++truth_written_;
    }
}

void CaptureNode::warnSkip(const std::string& message) {
  if (const auto left_out = skip_warnings_.admit("skipped frames"))
    log::warn(message, leftOutNote(*left_out));
}

void CaptureNode::warnSkipsLeftOut() {
  if (const int64_t left_out = skip_warnings_.takeLeftOut("skipped frames"); left_out > 0)
    log::warn(left_out, " more skipped frame(s) not named above (the summary counts every one)");
}

int CaptureNode::run() {
  // Interrupted while waiting: the player sees the stop too and publishes nothing.
  waitForProcesses(ctx_.lcm, ctx_.stop, settings_.wait_for, settings_.wait_timeout_s);
  ctx_.status.tick(true);
  FramePlayer player(ctx_.lcm, ctx_.stop, ctx_.status, settings_.player);
  const std::string& out = settings_.groundtruth_out;
  // A TUM folder's ground truth is the dataset's own (all of it, for evaluation against any subset).
  std::optional<TumTrajectoryStream> truth;
  if (!out.empty() && from_dataset_) {
    if (dataset_truth_.empty()) {
      log::warn("no ground truth for ", source_->name(), "; ", out, " not written");
    } else {
      dataset_truth_out_.emplace(out,
                                 "the dataset's ground truth, camera to world" +
                                     std::string(settings_.loops > 1 ? ", each pass shifted as played" : ""));
      writeTruthPass(0);
    }
  } else if (!out.empty()) {
    truth.emplace(out, "true camera poses of the frames played, camera to world");
  }
  warnSkipsLeftOut();  // the folder's own check, before the first frame
  const PlayerSummary summary =
      player.play(*source_, [&truth](const StampedPose& p) { truth ? truth->append(p) : void(); });
  warnSkipsLeftOut();
  if (truth) log::info("ground truth (", summary.groundtruth.size(), " poses) written to ", out);
  if (dataset_truth_out_) log::info("ground truth (", truth_written_, " poses) written to ", out);
  return summary.published > 0 ? 0 : 1;
}

}  // namespace bmp::capture

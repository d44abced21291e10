#include "capture/lcm/capture_node.hpp"

#include "bmp/common/log.hpp"
#include "bmp/lcm/wait_for_processes.hpp"
#include "capture/open_source.hpp"
#include "capture/tum_source.hpp"

namespace bmp::capture {

CaptureNode::CaptureNode(ProcessContext& ctx, CaptureSettings settings)
    : ctx_(ctx),
      settings_(std::move(settings)),
      source_(openFrameSource(settings_, [](const std::string& m) { log::warn(m); })) {}

int CaptureNode::run() {
  // Interrupted while waiting: the player sees the stop too and publishes nothing.
  waitForProcesses(ctx_.lcm, ctx_.stop, settings_.wait_for, settings_.wait_timeout_s);
  ctx_.status.tick(true);
  FramePlayer player(ctx_.lcm, ctx_.stop, ctx_.status, settings_.player);
  const PlayerSummary summary = player.play(*source_);
  writeGroundTruth(summary);
  return summary.published > 0 ? 0 : 1;
}

void CaptureNode::writeGroundTruth(const PlayerSummary& summary) const {
  const std::string& out = settings_.groundtruth_out;
  if (out.empty()) return;
  // A TUM folder's ground truth is the dataset's own (all of it, for evaluation against any subset).
  const auto* tum = dynamic_cast<const TumSource*>(source_.get());
  const Trajectory& gt = tum ? tum->index().groundtruth : summary.groundtruth;
  if (gt.empty()) {
    log::warn("no ground truth for ", source_->name(), "; ", out, " not written");
    return;
  }
  writeTumTrajectory(out, gt);
  log::info("ground truth (", gt.size(), " poses) written to ", out);
}

}  // namespace bmp::capture

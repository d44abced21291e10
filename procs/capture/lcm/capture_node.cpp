#include "capture/lcm/capture_node.hpp"

#include <optional>

#include "bmp/common/log.hpp"
#include "bmp/common/tum_trajectory.hpp"
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
  const std::string& out = settings_.groundtruth_out;
  // A TUM folder's ground truth is the dataset's own (all of it, for evaluation against any subset).
  const auto* tum = dynamic_cast<const TumSource*>(source_.get());
  std::optional<TumTrajectoryStream> truth;
  if (!out.empty() && tum) {
    if (tum->index().groundtruth.empty()) {
      log::warn("no ground truth for ", source_->name(), "; ", out, " not written");
    } else {
      writeTumTrajectory(out, tum->index().groundtruth);
      log::info("ground truth (", tum->index().groundtruth.size(), " poses) written to ", out);
    }
  } else if (!out.empty()) {
    truth.emplace(out, "true camera poses of the frames played, camera to world");
  }
  const PlayerSummary summary =
      player.play(*source_, [&truth](const StampedPose& p) { truth ? truth->append(p) : void(); });
  if (truth) log::info("ground truth (", summary.groundtruth.size(), " poses) written to ", out);
  return summary.published > 0 ? 0 : 1;
}

}  // namespace bmp::capture

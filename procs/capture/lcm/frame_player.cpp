#include "capture/lcm/frame_player.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include <bmp/detections_t.hpp>
#include <bmp/slam_pose_t.hpp>

#include "bmp/common/log.hpp"
#include "bmp/common/timing.hpp"
#include "bmp/lcm/wire_check.hpp"
#include "capture/lcm/frame_message.hpp"

namespace bmp::capture {

namespace {
constexpr double kLongWaitS = 10.0;  // a wait for the next frame this long is said in the log
}  // namespace

FramePlayer::FramePlayer(LcmNode& lcm, StopSignal& stop, StatusReporter& status, PlayerOptions options)
    : lcm_(lcm), stop_(stop), status_(status), options_(std::move(options)) {
  if (options_.mode == RateMode::kLockstep) {
    for (const auto& channel : options_.ack_channels) {
      last_answered_seq_[channel] = -1;
      lcm_.subscribeRaw(channel, [this](const void* data, uint32_t size, const ReceivedInfo& info) {
        onAnswer(data, size, info);
      });
    }
  }
  if (!options_.masks_out.empty()) std::filesystem::create_directories(options_.masks_out);
}

void FramePlayer::onAnswer(const void* data, uint32_t size, const ReceivedInfo& info) {
  // Both answer types carry the frame's seq and utime; wire::decode checks fingerprint and lengths.
  int64_t seq = -1, utime = -1;
  slam_pose_t pose;
  detections_t detections;
  std::string why_pose, why_detections;
  if (wire::decode(pose, data, size, why_pose)) {
    seq = pose.seq;
    utime = pose.utime;
  } else if (wire::decode(detections, data, size, why_detections)) {
    seq = detections.seq;
    utime = detections.utime;
  } else {
    lcm_.reportMalformed(info.channel, size,
                         "bmp.slam_pose_t (" + why_pose + ") or bmp.detections_t (" + why_detections + ")");
    return;
  }
  const auto sent = published_utime_.find(seq);
  if (sent == published_utime_.end() || sent->second != utime) {
    ++stray_answers_;  // counted in the heartbeat's malformed by reportMalformed, once
    lcm_.reportMalformed(info.channel, size,
                         "answer to a frame this capture published (seq " + std::to_string(seq) + ", utime " +
                             std::to_string(utime) + "); ignored");
    return;
  }
  int64_t& last = last_answered_seq_[info.channel];
  last = std::max(last, seq);
}

void FramePlayer::remember(int64_t seq, int64_t utime) {
  // Answers come back within the lockstep timeout; a few hundred frames cover any real delay.
  constexpr std::size_t kRemembered = 512;
  published_utime_[seq] = utime;
  while (published_utime_.size() > kRemembered) published_utime_.erase(published_utime_.begin());
}

double FramePlayer::resendAfterMs() const {
  double median_ms = 0.0;
  if (!answer_ms_.empty()) {
    std::vector<double> sorted(answer_ms_.begin(), answer_ms_.end());
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<long>(sorted.size() / 2), sorted.end());
    median_ms = sorted[sorted.size() / 2];
  }
  return std::max(options_.lockstep_resend_min_s * 1000.0, options_.lockstep_resend_factor * median_ms);
}

bool FramePlayer::waitForAck(const rgbd_frame_t& msg, PlayerSummary& summary) {
  const auto answered = [&] {
    for (const auto& [channel, last] : last_answered_seq_)
      if (last < msg.seq) return false;
    return true;
  };
  // Recent answer times set when a frame counts as late; a few dozen follow a change of pace.
  constexpr std::size_t kAnswerTimes = 32;
  const double resend_ms = resendAfterMs();
  const Stopwatch watch;
  Stopwatch since_sent;
  bool resent = false;
  while (!answered() && !stop_.requested()) {
    if (watch.elapsedMs() > options_.lockstep_timeout_s * 1000.0) return false;
    if (since_sent.elapsedMs() > resend_ms) {
      lcm_.publish(options_.channel, msg);  // consumers answer a repeat again, or let the pending one go
      since_sent.restart();
      ++summary.resent;
      resent = true;
    }
    lcm_.handle(10);
  }
  if (!resent) {  // a resent frame's time says how long the loss took, not how long answers take
    answer_ms_.push_back(watch.elapsedMs());
    if (answer_ms_.size() > kAnswerTimes) answer_ms_.pop_front();
  }
  return true;
}

void FramePlayer::writeMask(const CapturedFrame& frame) {
  if (options_.masks_out.empty() || frame.dynamic_mask.empty()) return;
  char name[64];
  std::snprintf(name, sizeof(name), "%.6f.png", frame.stamp);
  cv::imwrite((std::filesystem::path(options_.masks_out) / name).string(), frame.dynamic_mask);
}

PlayerSummary FramePlayer::play(FrameSource& source,
                                const std::function<void(const StampedPose&)>& on_truth) {
  PlayerSummary summary;
  Pacer pacer(options_.mode, options_.speed);
  const Stopwatch total;
  Stopwatch since_progress;
  const int64_t expected = source.size();
  log::info(
      "playing ", source.name(), ": ", expected, " frames, mode ", toString(options_.mode),
      options_.mode == RateMode::kRealtime ? ", speed x" + std::to_string(options_.speed) : std::string());
  while (!stop_.requested()) {
    std::optional<CapturedFrame> frame = source.next();
    if (!frame) break;
    // A long wait (a slow --speed, a gap in the stamps) is said, and slept with heartbeats and an ear for a
    // stop: one sleep to a stamp 1e10 s ahead hung capture silently, deaf to Ctrl-C.
    if (const double wait_s = pacer.waitFor(frame->stamp); wait_s > kLongWaitS)
      log::warn("the next frame (stamp ", frame->stamp, ") is due in ", static_cast<int64_t>(wait_s),
                " s at speed x", options_.speed, ": waiting (Ctrl-C stops)");
    if (!pacer.waitUntilDue(frame->stamp, [this] {
          status_.tick();
          return stop_.requested();
        }))
      break;
    if (stop_.requested()) break;
    if (frame->T_world_cam_true) {
      summary.groundtruth.push_back({frame->stamp, *frame->T_world_cam_true});
      if (on_truth) on_truth(summary.groundtruth.back());
    }
    writeMask(*frame);
    const int64_t seq = summary.published;
    const rgbd_frame_t msg = toFrameMessage(std::move(*frame), seq, source.camera(), source.name());
    remember(seq, msg.utime);
    lcm_.publish(options_.channel, msg);
    ++summary.published;
    status_.published();
    status_.processed();
    status_.dropped(source.skips().total() - status_.droppedCount());
    if (!source.skips().last_reason.empty()) status_.setMessage(source.skips().last_reason);
    if (options_.mode == RateMode::kLockstep && !waitForAck(msg, summary)) {
      ++summary.lockstep_timeouts;
      std::string missing;
      for (const auto& [channel, last] : last_answered_seq_)
        if (last < seq) missing += (missing.empty() ? "" : ", ") + channel;
      log::warn("no answer on ", missing, " for frame ", seq, " within ", options_.lockstep_timeout_s,
                " s; going on");
    }
    // Drain the socket even when not in lockstep, so our own subscriptions never back up.
    if (options_.mode != RateMode::kLockstep) lcm_.handle(0);
    status_.tick();
    if (since_progress.elapsedMs() >= options_.progress_every_s * 1000.0) {
      since_progress.restart();
      log::info("frame ", summary.published, "/", expected, " (",
                static_cast<int>(summary.published / (total.elapsedMs() / 1000.0)), " fps), skipped ",
                source.skips().total());
    }
  }
  summary.elapsed_s = total.elapsedMs() / 1000.0;
  summary.interrupted = stop_.requested();
  const SkipReport& skips = source.skips();
  char rate[32];
  std::snprintf(rate, sizeof(rate), "%.1f", summary.frames_per_second());
  log::info(
      "published ", summary.published, " frames in ", summary.elapsed_s, " s (", rate, " fps); skipped ",
      skips.total(), " (missing ", skips.missing_files, ", corrupt ", skips.corrupt_files, ", wrong size ",
      skips.wrong_size, ")",
      summary.lockstep_timeouts ? "; lockstep timeouts " + std::to_string(summary.lockstep_timeouts) : "",
      summary.resent ? "; resent (answers late) " + std::to_string(summary.resent) : "",
      stray_answers_ ? "; answers ignored (not for a frame we sent) " + std::to_string(stray_answers_) : "",
      summary.interrupted ? "; interrupted" : "");
  return summary;
}

}  // namespace bmp::capture

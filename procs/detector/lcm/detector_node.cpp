#include "detector/lcm/detector_node.hpp"

#include <poll.h>

#include <string>

#include "bmp/common/log.hpp"
#include "bmp/lcm/conversions.hpp"
#include "detector/lcm/detections_message.hpp"

namespace bmp::detector {

namespace {

Detector loadDetector(const DetectorSettings& settings) {
  try {
    return Detector(settings.detector, Config::fromFile(settings.dynamic_classes_path));
  } catch (const ModelError& e) {
    throw ConfigError(e.what());
  }
}

}  // namespace

DetectorNode::DetectorNode(ProcessContext& ctx, const DetectorSettings& settings)
    : ctx_(ctx),
      settings_(settings),
      detector_(loadDetector(settings_)),
      model_name_(detector_.modelName()),
      worker_(detector_, settings_.mode, settings_.queue_capacity, [this] { wakeup_.notify(); }) {
  log::info("model ", model_name_, " (", settings_.detector.modelSpec().path, ") ready; mode ",
            toString(settings_.mode), ", ", settings_.frames_channel, " -> ", settings_.detections_channel);
  ctx_.lcm.subscribe<rgbd_frame_t>(settings_.frames_channel,
                                   [this](const rgbd_frame_t& msg, const ReceivedInfo&) { receive(msg); });
}

void DetectorNode::receive(const rgbd_frame_t& msg) {
  const auto refuse = [&](const std::string& why, SkipAnswer how) {
    FrameResult failed;
    failed.seq = msg.seq;
    failed.utime = msg.utime;
    failed.error = why;
    skip(failed, how);
  };
  const FrameStream::Verdict verdict = stream_.accept(msg);
  if (verdict.repeat)
    return last_answer_.answerRepeat(ctx_.lcm, settings_.detections_channel, msg.seq, msg.utime);
  ctx_.status.received();  // a repeat is not a frame of its own
  ctx_.status.lost(verdict.lost_before);
  if (!verdict.ok)
    return refuse(verdict.reason, verdict.copies_accepted ? SkipAnswer::kNone : SkipAnswer::kOnce);
  if (!verdict.reason.empty()) log::warn("frame seq ", msg.seq, ": ", verdict.reason);  // e.g. a new camera
  FrameJob job;
  job.seq = msg.seq;
  job.utime = msg.utime;
  try {
    job.color = fromMsg(msg.color);
  } catch (const ImageError& e) {
    return refuse(std::string("colour image: ") + e.what(), SkipAnswer::kRemembered);
  }
  // Waits here in 'every' mode while the queue is full; counts the frame it displaced in 'latest' mode.
  ctx_.status.dropped(static_cast<int64_t>(worker_.submit(std::move(job))));
}

void DetectorNode::skip(const FrameResult& failed, SkipAnswer how) {
  const std::string warning = "frame seq " + std::to_string(failed.seq) + ": " + failed.error + "; skipped";
  if (const auto left_out = warnings_.admit("skipped frames")) log::warn(warning, leftOutNote(*left_out));
  ctx_.status.malformed();
  ctx_.status.setMessage(warning);
  const detections_t msg = toDetectionsMessage(failed, model_name_);
  if (how == SkipAnswer::kOnce)
    ctx_.lcm.publish(settings_.detections_channel, msg);
  else if (how == SkipAnswer::kRemembered)
    answer(msg);
}

void DetectorNode::answer(const detections_t& msg) {
  last_answer_.remember(msg);
  ctx_.lcm.publish(settings_.detections_channel, msg);
}

void DetectorNode::publishResults() {
  for (const auto& result : worker_.takeResults()) {
    if (!result.ok) {
      skip(result);
      continue;
    }
    answer(toDetectionsMessage(result, model_name_));
    ctx_.status.processed();
    frame_times_.add(result.total_ms);
    ctx_.status.published();
  }
}

int DetectorNode::run() {
  while (!ctx_.stop.requested()) {
    // Wakes for a frame or for a finished result, whichever comes first; the timeout keeps the heartbeat.
    pollfd fds[2] = {{ctx_.lcm.raw().getFileno(), POLLIN, 0}, {wakeup_.fd(), POLLIN, 0}};
    if (poll(fds, 2, 200) > 0 && (fds[0].revents & POLLIN) && !ctx_.lcm.handle(0)) {
      log::error("LCM receive failed");
      return 1;
    }
    wakeup_.clear();
    publishResults();
    ctx_.status.tick();
  }
  // Received but not answered: waiting when the stop came. Counted as dropped, so every frame received is
  // accounted for (processed, dropped, or refused as malformed). The worker is stopped first: a frame
  // finishing between the answers and the count was neither.
  worker_.finish();  // the frame in progress is answered
  publishResults();
  const std::size_t unfinished = worker_.unfinished();
  ctx_.status.dropped(static_cast<int64_t>(unfinished));
  log::info("processed ", ctx_.status.processedCount(), " of ", ctx_.status.receivedCount(),
            " frame(s), dropped ", ctx_.status.droppedCount(), " (", unfinished,
            " of them not yet processed at exit), malformed ", ctx_.status.malformedCount(),
            ", resent by capture ", stream_.repeats(), " (", last_answer_.answeredAgain(),
            " answered again); per frame ", frame_times_.empty() ? std::string("-") : frame_times_.summary());
  return 0;
}

}  // namespace bmp::detector

// bmp-detector: YOLO detections, each box tagged with its dynamic level, for every RGB-D frame it processes.
// The LCM thread only receives and publishes; inference runs on the DetectionWorker's thread.
#include <poll.h>

#include <filesystem>
#include <optional>
#include <string>

#include <bmp/rgbd_frame_t.hpp>

#include "bmp/common/log.hpp"
#include "bmp/common/timing.hpp"
#include "bmp/lcm/conversions.hpp"
#include "bmp/lcm/process.hpp"
#include "detector/detection_worker.hpp"
#include "detector/detector.hpp"
#include "detector/lcm/detections_message.hpp"
#include "detector/wakeup.hpp"

namespace {

using namespace bmp::detector;

// A relative path in the configuration is relative to the folder of the file that names it.
std::string besideConfig(const bmp::Config& config, const std::string& path) {
  if (std::filesystem::path(path).is_absolute()) return path;
  const std::filesystem::path origin(config.origin());
  const auto dir = std::filesystem::is_regular_file(origin) ? origin.parent_path()
                                                            : std::filesystem::path(bmp::configDir());
  return (dir / path).string();
}

struct Settings {
  DetectorConfig detector;
  std::string dynamic_classes_path;
  QueueMode mode = QueueMode::kLatest;
  int queue_capacity = 64;
  std::string frames_channel;
  std::string detections_channel;
};

// Reads the whole configuration and rejects unknown keys before any work starts.
Settings readSettings(const bmp::ProcessContext& ctx) {
  Settings s;
  s.detector = detectorConfigFromYaml(ctx.config);
  s.dynamic_classes_path =
      besideConfig(ctx.config, ctx.config.get<std::string>("dynamic_classes", "dynamic_classes.yaml"));
  const bmp::Config process = ctx.config.section("process");
  std::string mode = process.get<std::string>("mode", "latest");
  s.queue_capacity = process.get<int>("queue_capacity", s.queue_capacity);
  const bmp::Config channels = ctx.config.section("channels");
  s.frames_channel = channels.get<std::string>("frames", bmp::channels::kFrames);
  s.detections_channel = channels.get<std::string>("detections", bmp::channels::kDetections);
  if (ctx.args.given("mode")) mode = ctx.args.value("mode");
  try {
    s.mode = parseQueueMode(mode);
  } catch (const std::invalid_argument& e) {
    throw bmp::ConfigError(ctx.config.origin() + ": key 'process.mode' or --mode: " + e.what());
  }
  if (s.queue_capacity < 1)
    throw bmp::ConfigError(ctx.config.origin() + ": key 'process.queue_capacity' must be >= 1");
  bmp::finishConfig(ctx);
  return s;
}

int run(bmp::ProcessContext& ctx) {
  const Settings settings = readSettings(ctx);
  const std::string& frames_channel = settings.frames_channel;
  const std::string& detections_channel = settings.detections_channel;
  // A missing or broken model is a configuration error: exit code 2 before any frame is read.
  std::optional<Detector> detector_storage;
  try {
    detector_storage.emplace(settings.detector, bmp::Config::fromFile(settings.dynamic_classes_path));
  } catch (const ModelError& e) {
    throw bmp::ConfigError(e.what());
  }
  Detector& detector = *detector_storage;
  bmp::log::info("model ", detector.modelName(), " (", settings.detector.modelSpec().path, ") ready; mode ",
                 toString(settings.mode), ", ", frames_channel, " -> ", detections_channel);

  const std::string model_name = detector.modelName();
  // A frame that cannot be processed is warned about, counted, and still answered (no boxes, the reason), so
  // lockstep never waits in vain.
  const auto skip = [&](const FrameResult& failed) {
    const std::string warning = "frame seq " + std::to_string(failed.seq) + ": " + failed.error + "; skipped";
    bmp::log::warn(warning);
    ctx.status.malformed();
    ctx.status.setMessage(warning);
    ctx.lcm.publish(detections_channel, toDetectionsMessage(failed, model_name));
  };
  Wakeup wakeup;
  DetectionWorker worker(detector, settings.mode, static_cast<std::size_t>(settings.queue_capacity),
                         [&wakeup] { wakeup.notify(); });
  ctx.lcm.subscribe<bmp::rgbd_frame_t>(
      frames_channel, [&](const bmp::rgbd_frame_t& msg, const bmp::ReceivedInfo&) {
        ctx.status.received();
        FrameJob job;
        job.seq = msg.seq;
        job.utime = msg.utime;
        try {
          job.color = bmp::fromMsg(msg.color);
        } catch (const bmp::ImageError& e) {
          FrameResult failed;
          failed.seq = msg.seq;
          failed.utime = msg.utime;
          failed.error = std::string("colour image: ") + e.what();
          skip(failed);
          return;
        }
        ctx.status.dropped(static_cast<int64_t>(worker.submit(std::move(job))));
      });
  ctx.status.tick(true);  // the first heartbeat also tells others we are subscribed

  bmp::TimingStats frame_times;
  while (!ctx.stop.requested()) {
    pollfd fds[2] = {{ctx.lcm.raw().getFileno(), POLLIN, 0}, {wakeup.fd(), POLLIN, 0}};
    if (poll(fds, 2, 200) > 0 && (fds[0].revents & POLLIN) && !ctx.lcm.handle(0)) {
      bmp::log::error("LCM receive failed");
      return 1;
    }
    wakeup.clear();
    for (const auto& result : worker.takeResults()) {
      if (!result.ok) {
        skip(result);
        continue;
      }
      ctx.lcm.publish(detections_channel, toDetectionsMessage(result, model_name));
      ctx.status.processed();
      frame_times.add(result.total_ms);
      ctx.status.published();
    }
    ctx.status.tick();
  }
  bmp::log::info("processed ", ctx.status.processedCount(), " of ", ctx.status.receivedCount(),
                 " frame(s), dropped ", ctx.status.droppedCount(), ", malformed ",
                 ctx.status.malformedCount(), ", not yet processed at exit ", worker.pending(),
                 "; per frame ", frame_times.empty() ? std::string("-") : frame_times.summary());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  bmp::ProcessSpec spec;
  spec.name = "bmp-detector";
  spec.summary =
      "Runs YOLO (OpenCV DNN) on the colour image of each RGB-D frame and publishes the boxes, each with its "
      "class, score and dynamic level (high / medium / low, config/dynamic_classes.yaml). In mode 'latest' "
      "a frame arriving while the detector is busy replaces the waiting one (drops are counted in "
      "PROCESS_STATUS); in mode 'every' every frame is processed, for lockstep runs.";
  spec.default_config = "detector.yaml";
  spec.add_options = [](bmp::ArgParser& args) {
    args.addOption("mode", "latest|every", "override process.mode of the configuration");
  };
  spec.run = run;
  return bmp::runProcess(argc, argv, spec);
}

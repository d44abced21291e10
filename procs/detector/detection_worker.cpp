#include "detector/detection_worker.hpp"

#include <stdexcept>

#include "bmp/common/timing.hpp"

namespace bmp::detector {

QueueMode parseQueueMode(const std::string& text) {
  if (text == "latest") return QueueMode::kLatest;
  if (text == "every") return QueueMode::kEvery;
  throw std::invalid_argument("mode must be 'latest' or 'every', got '" + text + "'");
}

const char* toString(QueueMode mode) {
  return mode == QueueMode::kLatest ? "latest" : "every";
}

FrameResult processFrame(Detector& detector, const FrameJob& job) {
  FrameResult result;
  result.seq = job.seq;
  result.utime = job.utime;
  const Stopwatch watch;
  cv::Mat bgr;
  try {
    bgr = decodeImage(job.color);
  } catch (const ImageError& e) {
    result.error = std::string("colour image: ") + e.what();
    return result;
  }
  if (bgr.type() != CV_8UC3) {
    result.error = "colour image is not 3-channel 8-bit";
    return result;
  }
  result.stages.decode_ms = watch.elapsedMs();
  result.detections = detector.detect(bgr, &result.stages);
  result.width = bgr.cols;
  result.height = bgr.rows;
  result.total_ms = watch.elapsedMs();
  result.ok = true;
  return result;
}

DetectionWorker::DetectionWorker(Detector& detector, QueueMode mode, std::size_t capacity,
                                 std::function<void()> on_result)
    : detector_(detector),
      queue_(mode == QueueMode::kLatest ? 1 : capacity,
             mode == QueueMode::kLatest ? WhenFull::kDropOldest : WhenFull::kWait),
      on_result_(std::move(on_result)),
      thread_([this] { run(); }) {}

DetectionWorker::~DetectionWorker() {
  finish();
}

void DetectionWorker::finish() {
  stopping_ = true;
  queue_.close();
  if (thread_.joinable()) thread_.join();
}

std::size_t DetectionWorker::submit(FrameJob job) {
  return queue_.push(std::move(job));
}

std::vector<FrameResult> DetectionWorker::takeResults() {
  std::lock_guard<std::mutex> lock(results_mutex_);
  std::vector<FrameResult> out;
  out.swap(results_);
  return out;
}

void DetectionWorker::run() {
  // A frame taken is processed even when the stop came meanwhile: it is in no queue to be counted from.
  while (!stopping_) {
    std::optional<FrameJob> job = queue_.pop();
    if (!job) break;
    busy_ = true;
    FrameResult result;
    try {
      result = processFrame(detector_, *job);
    } catch (const std::exception& e) {
      // OpenCV may throw on an image it cannot handle: report it for this frame and keep going.
      result.seq = job->seq;
      result.utime = job->utime;
      result.error = std::string("detection failed: ") + e.what();
    }
    {
      std::lock_guard<std::mutex> lock(results_mutex_);
      results_.push_back(std::move(result));
    }
    busy_ = false;
    if (on_result_) on_result_();
  }
}

}  // namespace bmp::detector

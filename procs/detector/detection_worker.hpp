#pragma once
// Inference on its own thread (the paper's detection thread): frames go in through a bounded queue, results
// come out through takeResults(), so the thread that owns the LCM connection never waits for the network.
#include <atomic>
#include <cstdint>
#include <functional>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "bmp/common/bounded_queue.hpp"
#include "bmp/common/image_codec.hpp"
#include "detector/detector.hpp"

namespace bmp::detector {

// How frames reach the worker. kLatest: one waits at a time and a newer frame replaces it (counted as
// dropped), so a slow detector always works on the freshest image. kEvery: frames queue up to a capacity
// and the receiver waits when it is full, so lockstep runs process every frame.
enum class QueueMode { kLatest, kEvery };

// Throws std::invalid_argument for anything but "latest" or "every".
QueueMode parseQueueMode(const std::string& text);
const char* toString(QueueMode mode);

struct FrameJob {
  int64_t seq = 0;
  int64_t utime = 0;
  EncodedImage color;  // decoded on the worker: decoding is part of the detector's time
};

struct FrameResult {
  int64_t seq = 0;
  int64_t utime = 0;
  bool ok = false;
  std::string error;  // why the frame was skipped, when !ok
  std::vector<Detection> detections;
  int width = 0;
  int height = 0;
  double total_ms = 0.0;  // decode + letterbox + inference + NMS
  StageTimes stages;
};

// Decodes and detects one frame; an undecodable image gives !ok with the reason.
FrameResult processFrame(Detector& detector, const FrameJob& job);

class DetectionWorker {
 public:
  // capacity: frames waiting in kEvery mode (at least 1); kLatest holds one. on_result is called on the
  // worker thread after each result is queued (e.g. Wakeup::notify).
  DetectionWorker(Detector& detector, QueueMode mode, std::size_t capacity,
                  std::function<void()> on_result = nullptr);
  ~DetectionWorker();  // finishes the frame in progress, discards the rest
  DetectionWorker(const DetectionWorker&) = delete;
  DetectionWorker& operator=(const DetectionWorker&) = delete;

  // Returns how many waiting frames this one displaced ("latest" mode); may wait in "every" mode.
  std::size_t submit(FrameJob job);
  // Results finished since the last call, in processing order.
  std::vector<FrameResult> takeResults();
  // Stops the worker: the frame in progress finishes (its result is taken as any other), the waiting ones
  // stay unprocessed. Counting those only after this leaves no frame between the two counts.
  void finish();
  // Frames waiting for the worker, and the one in progress: not answered if the process stops now.
  std::size_t unfinished() const { return queue_.size() + (busy_ ? 1 : 0); }

 private:
  void run();
  Detector& detector_;
  BoundedQueue<FrameJob> queue_;
  std::function<void()> on_result_;
  std::mutex results_mutex_;
  std::vector<FrameResult> results_;
  std::atomic<bool> stopping_{false};
  std::atomic<bool> busy_{false};  // a frame taken from the queue whose result is not yet in results_
  std::thread thread_;             // last: starts after everything it uses exists
};

}  // namespace bmp::detector

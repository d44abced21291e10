#pragma once
// Where frames come from: a TUM-format folder or the synthetic scene. The capture process pulls frames from
// a FrameSource and paces and publishes them; nothing here knows about LCM.
#include <cstdint>
#include <optional>
#include <string>

#include <opencv2/core.hpp>

#include "bmp/common/camera_model.hpp"
#include "bmp/common/image_codec.hpp"
#include "bmp/common/se3.hpp"

namespace bmp::capture {

struct CapturedFrame {
  int64_t index = 0;                    // position in the source (0-based), before --start/--every selection
  double stamp = 0.0;                   // colour capture time, seconds
  double depth_stamp = 0.0;             // depth capture time, seconds
  EncodedImage color;                   // kBgr8: file bytes (PNG/JPEG) or raw pixels
  EncodedImage depth;                   // kMono16: file bytes (PNG) or raw pixels
  std::optional<SE3> T_world_cam_true;  // ground truth, when the source knows it exactly
  cv::Mat dynamic_mask;                 // CV_8UC1, 255 on moving objects; empty when unknown
};

// Counts of what a source had to skip, with the last reason, for the status heartbeat and the summary.
struct SkipReport {
  int64_t missing_files = 0;
  int64_t corrupt_files = 0;
  int64_t wrong_size = 0;
  std::string last_reason;
  int64_t total() const { return missing_files + corrupt_files + wrong_size; }
};

class FrameSource {
 public:
  virtual ~FrameSource() = default;
  // The next valid frame, or nullopt at the end. Invalid frames are skipped and counted, never returned.
  virtual std::optional<CapturedFrame> next() = 0;
  virtual const CameraIntrinsics& camera() const = 0;
  virtual std::string name() const = 0;
  // Frames the source will offer at most (before skips), for progress output.
  virtual int64_t size() const = 0;
  virtual const SkipReport& skips() const = 0;
};

}  // namespace bmp::capture

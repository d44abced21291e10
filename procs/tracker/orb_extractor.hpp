#pragma once
// ORB features: FAST corners over a scale pyramid, spread evenly over each level by grid bucketing (the
// strongest corner of every bucket first, then the second of every bucket, ...), oriented by intensity
// centroid, described by a rotated 256-bit binary test pattern of our own (fixed-seed Gaussian pairs).
#include <cstdint>
#include <cstring>
#include <vector>

#include <opencv2/core.hpp>

#include "tracker/tracker_options.hpp"

namespace bmp::tracker {

// Scale of every pyramid level and the matching measurement variance (one pixel at that level).
struct ScalePyramid {
  ScalePyramid(int levels, double factor);
  int levels;
  double factor;
  double log_factor;
  std::vector<double> scale;   // level -> factor^level
  std::vector<double> sigma2;  // level -> scale^2
  std::vector<double> inv_sigma2;
};

struct OrbFeatures {
  std::vector<cv::KeyPoint> keys;  // level-0 pixels of the input image; octave = level, angle in degrees
  cv::Mat descriptors;             // keys.size() x 32, CV_8U
};

// Parts of the image that should get fewer keypoints than their area's share: buckets whose centre lies in
// one of `boxes` (level-0 pixels) count `share` of their area when the budget is split.
// Keypoints on a mover cannot hold the pose: the budget they would take goes to the static scene.
struct SparseRegions {
  std::vector<cv::Rect2f> boxes;
  double share = 1.0;
};

class OrbExtractor {
 public:
  explicit OrbExtractor(const OrbOptions& options);
  // Thread-safe (no mutable state). gray: CV_8UC1.
  OrbFeatures extract(const cv::Mat& gray, const SparseRegions& sparse = {}) const;
  const ScalePyramid& pyramid() const { return pyramid_; }

 private:
  // sparse: its boxes in this level's pixels.
  void detectLevel(const cv::Mat& image, int target, const SparseRegions& sparse,
                   std::vector<cv::KeyPoint>& out) const;
  // Appends up to target of kept to out, round by round over the buckets `which` (indices into buckets,
  // each sorted by response); a last, partial round in bucket order, or by response when
  // strongest_last_round.
  static void spread(const std::vector<cv::KeyPoint>& kept, const std::vector<std::vector<int>>& buckets,
                     const std::vector<int>& which, int target, bool strongest_last_round,
                     std::vector<cv::KeyPoint>& out);
  float orientation(const cv::Mat& image, const cv::Point2f& pt) const;
  void describe(const cv::Mat& blurred, const cv::KeyPoint& kp, uint8_t* out) const;

  OrbOptions options_;
  ScalePyramid pyramid_;
  std::vector<int> per_level_;          // features wanted per level
  std::vector<int> circle_half_width_;  // of the orientation patch, per row offset
  // Per row offset v, 32 lanes for u = -15..16: u inside the circle (else 0), and v inside it (else 0).
  // The moments then come as multiply-adds of whole rows (orientation()).
  std::vector<int16_t> moment_u_, moment_v_;
  std::vector<float> pattern_x_, pattern_y_;  // 512 points: pairs (2k, 2k+1); apart, to rotate 4 at once
};

inline constexpr int kDescriptorBytes = 32;  // ORB: 256 binary tests

// Hamming distance of two 32-byte descriptors.
// Inline, and built with the CPU's popcount instruction where the build machine has one (CMakeLists): the
// matcher calls this millions of times a second, and a call to libgcc's software popcount per word cost more
// than the comparison itself.
inline int hamming(const uint8_t* a, const uint8_t* b) {
  int d = 0;
  for (int i = 0; i < kDescriptorBytes; i += 8) {
    uint64_t x, y;
    std::memcpy(&x, a + i, 8);
    std::memcpy(&y, b + i, 8);
    d += __builtin_popcountll(x ^ y);
  }
  return d;
}

}  // namespace bmp::tracker

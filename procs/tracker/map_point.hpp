#pragma once
// A 3-D landmark. All state is guarded by the Map's mutex (see map.hpp); nothing here locks.
#include <cstdint>
#include <map>
#include <memory>

#include <Eigen/Core>
#include <opencv2/core.hpp>

namespace bmp::tracker {

class KeyFrame;
struct FrameGeometry;

// Orders keyframes by id, so iteration (and so every result) does not depend on heap addresses.
struct KeyFrameIdLess {
  bool operator()(const KeyFrame* a, const KeyFrame* b) const;
};

class MapPoint {
 public:
  // id < 0 marks a temporary point: made from depth for the last frame only, never in the map.
  MapPoint(int64_t id, const Eigen::Vector3d& p_world, const cv::Mat& descriptor, int64_t first_kf_id);

  int64_t id;
  Eigen::Vector3d p_world;
  cv::Mat descriptor;  // 1 x 32: the observation closest (median Hamming) to all others
  std::map<KeyFrame*, int, KeyFrameIdLess> observations;  // keyframe -> keypoint index
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();       // mean viewing direction (unit)
  double min_distance = 0.0;                              // scale-invariance range of the descriptor
  double max_distance = 0.0;
  int visible = 1;  // frames in whose frustum it was
  int found = 1;    // frames that matched it as an inlier
  bool bad = false;
  int64_t first_kf_id;
  KeyFrame* reference = nullptr;          // keyframe whose observation defines the scale range
  float moving_probability = 0.5f;        // P(dynamic): the posterior of the keypoints it matched
  std::shared_ptr<MapPoint> replaced_by;  // set when fusion merged it into another point

  bool temporary() const { return id < 0; }
  double foundRatio() const { return static_cast<double>(found) / visible; }
  // Level at which a keypoint would observe it from `distance` metres.
  int predictLevel(double distance, const FrameGeometry& g) const;
  void updateNormalAndDepth(const FrameGeometry& g);
  void updateDescriptor();
  // Single-keyframe version for a point just created from depth.
  void initGeometry(const Eigen::Vector3d& camera_center, int level, const FrameGeometry& g);
};

}  // namespace bmp::tracker

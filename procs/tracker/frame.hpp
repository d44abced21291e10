#pragma once
// A frame's features (immutable once built, shared with the keyframe made from it) and the frame itself:
// its pose and its matches to map points.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "bmp/common/camera_model.hpp"
#include "bmp/common/se3.hpp"
#include "tracker/orb_extractor.hpp"
#include "tracker/tracker_options.hpp"

namespace bmp::tracker {

// Cell `cell` (a floor or ceil of a position over the cell width) clamped to [0, count): compared as a
// double before the cast, since casting a NaN or far-off double to int is undefined. NaN gives cell 0.
inline int clampedCell(double cell, int count) {
  if (!(cell > 0.0)) return 0;
  return cell >= count - 1 ? count - 1 : static_cast<int>(cell);
}

class MapPoint;
class KeyFrame;

// Constants derived from the camera and the options, shared by every frame and keyframe of a run.
struct FrameGeometry {
  FrameGeometry(const CameraIntrinsics& intrinsics, const TrackerConfig& config);
  CameraModel camera;
  ScalePyramid pyramid;
  double fx, fy, cx, cy;
  double bf;           // fx * virtual baseline: u_right = u - bf / depth
  double close_depth;  // metres
  double min_depth, max_depth;
  double min_x, max_x, min_y, max_y;  // bounds of the undistorted image
  static constexpr int kGridCols = 64;
  static constexpr int kGridRows = 48;
  double grid_cell_w, grid_cell_h;
  bool inBounds(double u, double v) const { return u >= min_x && u < max_x && v >= min_y && v < max_y; }
  Eigen::Vector2d project(const Eigen::Vector3d& p_cam) const {
    return {fx * p_cam.x() / p_cam.z() + cx, fy * p_cam.y() / p_cam.z() + cy};
  }
};

// How much a keypoint may count: 1 normally, 0 excluded (the hook the dynamic-object stage drives).
// Called with the keypoint in distorted image pixels and its depth in metres (0 when none).
using KeypointWeightFn = std::function<float(const cv::KeyPoint& key, float depth)>;

struct Features {
  std::vector<cv::KeyPoint> keys;      // distorted image, level-0 pixels
  std::vector<Eigen::Vector2d> un;     // undistorted pixels
  cv::Mat descriptors;                 // N x 32, CV_8U
  std::vector<float> depth;            // metres, 0 where none or outside the valid range
  std::vector<float> weight;           // 0..1, scales a keypoint's information in optimisation
  std::vector<uint8_t> excluded;       // 1: takes no part in matching, optimisation or map points
  std::vector<std::vector<int>> grid;  // keypoint indices per cell, row-major kGridCols x kGridRows

  int size() const { return static_cast<int>(keys.size()); }
  const uint8_t* descriptor(int i) const { return descriptors.ptr<uint8_t>(i); }
  int level(int i) const { return keys[i].octave; }
  bool hasDepth(int i) const { return depth[i] > 0.0f; }
  double uRight(const FrameGeometry& g, int i) const {
    return depth[i] > 0 ? un[i].x() - g.bf / depth[i] : -1.0;
  }
  // Calls fn(i) for each keypoint within radius r of (u, v) on levels [min_level, max_level] (-1: any), in
  // grid order. Walks the grid in place: it runs for every projected point, so no list is built.
  template <class Fn>
  void forEachInArea(const FrameGeometry& g, double u, double v, double r, int min_level, int max_level,
                     Fn&& fn) const;
  template <class Fn>
  void forEachInArea(const FrameGeometry& g, double u, double v, double r, Fn&& fn) const {
    forEachInArea(g, u, v, r, -1, -1, std::forward<Fn>(fn));
  }
  int numExcluded() const;
  // Keypoints with depth that are not excluded, nearest first: the order new points are made from depth.
  std::vector<int> nearestWithDepth() const;
};

template <class Fn>
void Features::forEachInArea(const FrameGeometry& g, double u, double v, double r, int min_level,
                             int max_level, Fn&& fn) const {
  if (!(std::isfinite(u) && std::isfinite(v) && r >= 0.0)) return;  // a projection gone wrong finds nothing
  const int c0 = clampedCell(std::floor((u - r - g.min_x) / g.grid_cell_w), FrameGeometry::kGridCols);
  const int c1 = clampedCell(std::ceil((u + r - g.min_x) / g.grid_cell_w), FrameGeometry::kGridCols);
  const int r0 = clampedCell(std::floor((v - r - g.min_y) / g.grid_cell_h), FrameGeometry::kGridRows);
  const int r1 = clampedCell(std::ceil((v + r - g.min_y) / g.grid_cell_h), FrameGeometry::kGridRows);
  for (int row = r0; row <= r1; ++row) {
    for (int col = c0; col <= c1; ++col) {
      for (int i : grid[row * FrameGeometry::kGridCols + col]) {
        const int level = keys[i].octave;
        if (min_level >= 0 && level < min_level) continue;
        if (max_level >= 0 && level > max_level) continue;
        const double du = un[i].x() - u, dv = un[i].y() - v;
        if (std::abs(du) < r && std::abs(dv) < r) fn(i);
      }
    }
  }
}

// The depth at pixel (u, v) in metres: depth CV_32FC1 metres, else CV_16UC1 raw units over depth_scale.
inline double depthMetresAt(const cv::Mat& depth, int u, int v, double depth_scale) {
  return depth.type() == CV_32FC1 ? depth.at<float>(v, u) : depth.at<uint16_t>(v, u) / depth_scale;
}

// Builds the per-keypoint data from ORB output. depth: CV_16UC1 (raw units, scaled by the camera's
// depth_scale) or CV_32FC1 metres, registered to the colour image; may be empty.
std::shared_ptr<const Features> buildFeatures(OrbFeatures orb, const cv::Mat& depth, const FrameGeometry& g,
                                              const KeypointWeightFn& weight_fn,
                                              const cv::Mat& exclusion_mask);

class Frame {
 public:
  Frame() = default;
  Frame(int64_t seq, double stamp, std::shared_ptr<const Features> features);

  int64_t seq = -1;
  double stamp = 0.0;
  std::shared_ptr<const Features> features;
  std::vector<std::shared_ptr<MapPoint>> points;  // per keypoint, null when unmatched
  std::vector<uint8_t> outlier;                   // per keypoint, set by pose optimisation
  // The dynamic stage's view of each keypoint (dynamic_stage.hpp): this frame's box observation (1 z = d,
  // 0 z = s; empty when no boxes came for the frame), P(dynamic), and whether that is over the threshold.
  // A dynamic keypoint keeps its match (its probability travels on) but takes no part in the pose.
  std::vector<int8_t> box_z;
  std::vector<float>
      box_moving_share;  // per box: its keypoints seen moving last frame (medium boxes' evidence)
  bool box_z_stand_in =
      false;  // any box_z comes from stand-in boxes (real time: the frame's own answer is late)
  std::vector<float> moving;
  std::vector<uint8_t> dynamic;
  bool isDynamic(std::size_t i) const { return dynamic[i] != 0; }
  // kGeometric: each keypoint's geometric verdict this frame, -1 none, 0 where it should be, 1 moved against
  // the camera motion. Evidence from the keypoints alone (no box in it): the next frame's medium boxes count
  // as moving by it, so a chair's own box cannot keep it "moving" (empty in the other modes).
  std::vector<int8_t> moved;
  // A keypoint matched to no map point but tracked from the last frame's keypoints (keypoint_tracks.hpp):
  // where its track began, in the world (valid where anchored[i]), so the geometric observation sees how
  // far it has moved since, not only since the last frame.
  std::vector<Eigen::Vector3d> anchor;
  std::vector<uint8_t> anchored;
  int numDynamic() const;
  // Set by the local map's pose solve, the frame's last: how well its inliers pin the position
  // (pose_optimizer.hpp positionStd).
  double position_std_m = std::numeric_limits<double>::infinity();

  void setPose(const SE3& T_world_cam);
  const SE3& T_world_cam() const { return T_world_cam_; }
  const SE3& T_cam_world() const { return T_cam_world_; }
  Eigen::Vector3d center() const { return T_world_cam_.translation(); }
  int numMatches() const;
  void clearMatches();

 private:
  SE3 T_world_cam_ = SE3::Identity();
  SE3 T_cam_world_ = SE3::Identity();
};

}  // namespace bmp::tracker

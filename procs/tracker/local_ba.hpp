#pragma once
// Local bundle adjustment: keyframe poses and point positions of a covisible window, with keyframes that
// only see those points held fixed. A plain data problem, so it can be tested without a map; local_mapper
// fills it from the map and writes the result back.
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "bmp/common/se3.hpp"
#include "tracker/pose_optimizer.hpp"
#include "tracker/tracker_options.hpp"

namespace bmp::tracker {

struct BaKeyFrame {
  int64_t id = 0;
  SE3 T_cam_world = SE3::Identity();
  bool fixed = false;
};

struct BaPoint {
  int64_t id = 0;
  Eigen::Vector3d p_world = Eigen::Vector3d::Zero();
};

struct BaObservation {
  int keyframe = 0;  // index into BaProblem::keyframes
  int point = 0;     // index into BaProblem::points
  Eigen::Vector2d uv = Eigen::Vector2d::Zero();
  double u_right = -1.0;  // negative: no depth
  double information = 1.0;
  double weight = 1.0;
  bool outlier = false;  // out: rejected by the chi-square test
};

struct BaProblem {
  std::vector<BaKeyFrame> keyframes;
  std::vector<BaPoint> points;
  std::vector<BaObservation> observations;
};

struct BaSummary {
  int residuals = 0;
  int outliers = 0;
  double initial_cost = 0.0;
  double final_cost = 0.0;
};

// Two stages: Huber over all observations, then again without the chi-square outliers. Updates poses and
// points in place and flags outliers.
BaSummary solveLocalBa(BaProblem& problem, const PoseCamera& camera, const MappingOptions& mapping,
                       const PoseOptimizerOptions& thresholds);

}  // namespace bmp::tracker

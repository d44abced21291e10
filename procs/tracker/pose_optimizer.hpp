#pragma once
// Pose-only optimisation: the camera pose that best reprojects known 3-D points onto their keypoints, with
// a Huber kernel and rounds of chi-square outlier classification (an outlier may come back in a later round).
#include <vector>

#include <Eigen/Core>

#include "bmp/common/se3.hpp"
#include "tracker/tracker_options.hpp"

namespace bmp::tracker {

struct PoseObservation {
  Eigen::Vector3d p_world;
  Eigen::Vector2d uv;        // undistorted pixel
  double u_right = -1.0;     // u - bf / depth; negative: no depth, 2-D residual
  double information = 1.0;  // 1 / sigma^2 of the keypoint's level: decides outliers
  double weight = 1.0;       // scales the cost only (per-keypoint hook for dynamic features)
  bool outlier = false;      // in: start as outlier; out: classification after the last round
};

struct PoseCamera {
  double fx = 0, fy = 0, cx = 0, cy = 0, bf = 0;
};

// A Gaussian prior on the camera's position (its centre in the world), isotropic.
struct PositionPrior {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  double sigma_m = 0.0;
};

// Refines T_cam_world in place; returns the number of inliers. With a prior the position is also held to it.
int optimizePose(SE3& T_cam_world, std::vector<PoseObservation>& observations, const PoseCamera& camera,
                 const PoseOptimizerOptions& options, const PositionPrior* prior = nullptr);

// How well the inlier observations alone pin the camera's position: the standard deviation (metres) of the
// camera centre along its worst-determined direction, from the covariance of the weighted least-squares fit
// (each keypoint at its level's sigma, weighted as in the solve; no prior). Far points in one band of the
// image leave a sideways shift with a turn barely seen, and this says by how much. Infinity when the inliers
// do not determine the pose.
double positionStd(const SE3& T_cam_world, const std::vector<PoseObservation>& observations,
                   const PoseCamera& camera);

// Squared whitened error of one observation under a pose (the statistic compared with chi2).
double poseChi2(const SE3& T_cam_world, const PoseObservation& obs, const PoseCamera& camera);

}  // namespace bmp::tracker

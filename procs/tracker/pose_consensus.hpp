#pragma once
// A consensus pre-pass for pose-only optimisation. Huber alone settles between two motions when a large
// group of matches moves differently (a person walking close to the camera pulls the pose along the weakly
// constrained directions). Before optimising, hypotheses from three matches with depth (rigid alignment of
// the back-projected keypoints to their map points) compete with the prediction on the observations they
// explain; the winner starts the optimisation and the matches it does not explain start as outliers. With
// consensus_graded (the default) each explained match counts by how well (1 - chi2 / limit, as MSAC
// scores), otherwise 1: a near rigid mover (a pushed cart) and the far background can both sit within the
// limit of the wrong motion, which then explains more matches than the right one, but explains them worse.
#include <vector>

#include "bmp/common/se3.hpp"
#include "tracker/pose_optimizer.hpp"
#include "tracker/tracker_options.hpp"

namespace bmp::tracker {

struct ConsensusResult {
  SE3 T_cam_world = SE3::Identity();
  double support = 0.0;        // observations within the (loose) scoring threshold
  double prior_support = 0.0;  // the same for the prediction
  bool from_sample = false;    // a sampled hypothesis beat the prediction
};

// Deterministic (fixed-seed sampling). Sets outlier on the observations the winner does not explain.
ConsensusResult findConsensusPose(const SE3& T_cam_world_prior, std::vector<PoseObservation>& observations,
                                  const PoseCamera& camera, const PoseOptimizerOptions& options);

}  // namespace bmp::tracker

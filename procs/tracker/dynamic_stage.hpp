#pragma once
// The dynamic stage: which keypoints lie on something that moves, frame by frame. Read this with
// Tracker::track. For each frame:
//   1. observe()      the detector's boxes for this frame, if they came, give each keypoint z = d or z = s
//                     (the paper's region test; with DynamicMode::kDepth and up, a person's box is cut to
//                     the person by depth; a chair or cup box counts only when held or seen moving);
//   2. applyPriors()  before each pose optimisation: each keypoint's prior is the posterior of the map point
//                     it matched (else 0.5), updated by z;
//   3. conclude()     after the final pose: in every Bayesian mode a keypoint matched to no map point but
//                     tracked to a last-frame keypoint takes that keypoint's posterior as prior (the
//                     paper's); with kGeometric, besides: an unmatched keypoint's prior becomes that of
//                     matched neighbours at its depth; each matched point's residual against the camera
//                     motion is a second observation; so is each unmatched keypoint's residual against its
//                     last-frame keypoint, tracked over a wide window (keypoint_tracks.hpp), which also
//                     gives it that keypoint's posterior as prior. Inside a moving region only a large
//                     residual is an observation (a person standing still keeps the box's word);
//   4. commit()       once the frame is known to be tracked: the map points take the posteriors (a frame
//                     posed wrongly would mark the map's static points as moving, as its residuals are).
// A keypoint over the threshold keeps its match, so its probability travels on, but takes no part in the
// pose, new map points or local BA.
#include <vector>

#include <opencv2/core.hpp>

#include "tracker/dynamic_regions.hpp"
#include "tracker/frame.hpp"
#include "tracker/keypoint_window_grid.hpp"
#include "tracker/moving_probability.hpp"
#include "tracker/tracker_options.hpp"

namespace bmp::tracker {

class DynamicStage {
 public:
  DynamicStage(const DynamicOptions& options, const PoseOptimizerOptions& pose);

  bool enabled() const { return options_.mode != DynamicMode::kNone; }
  // boxes: the detector's for this frame, or null when none came. last: the previous frame (or null),
  // whose keypoints seen moving (Frame::moved) are the evidence that a medium box moves.
  void observe(Frame& frame, const std::vector<ObjectBox>* boxes, const Frame* last) const;
  void applyPriors(Frame& frame) const;
  // last: the previous frame (or null); its keypoints are tracked to this frame's unmatched ones
  // (keypoint_tracks.hpp), whose prior they become; with kGeometric each track is judged as a matched
  // point is.
  void conclude(Frame& frame, const FrameGeometry& g, const Frame* last) const;
  // The matched map points take the frame's posteriors (after conclude, for a frame that tracked).
  void commit(const Frame& frame) const;
  // A keyframe's late boxes (they came after it was tracked): it and its map points take the observation,
  // in place of the stand-in boxes' observation when its frame was observed with those
  // (KeyFrame::stand_in_z).
  void observeLate(KeyFrame& kf, const std::vector<ObjectBox>& boxes) const;
  // The boxes that count as moving for these keypoints, each cut to the mover by depth when configured:
  // per box, the depth band [near, far] in metres of the mover (0, inf when not refined).
  struct MovingRegion {
    cv::Rect2f box;
    float near_m = 0.0f, far_m = 0.0f;  // far_m = 0: the whole box
  };
  std::vector<MovingRegion> movingRegions(const Features& f, const std::vector<ObjectBox>& boxes,
                                          const std::vector<float>& moving_share) const;
  // The per-pixel dynamic mask of a frame (CV_8UC1, 255 dynamic): its moving regions (by depth when
  // refined), a disk around every dynamic keypoint and, with kGeometric, each cluster of dynamic keypoints
  // as a region: its bounding box, grown by the disk's radius, at its depths (a mover no detector knows has
  // only some of its keypoints judged; the mapper must leave out the rest of it too). moving_share: each
  // box's keypoints seen moving, as the frame's observation counted them (Frame::box_moving_share, or
  // lateMovingShare), so a chair pushed along is masked as it was kept out. depth: CV_16UC1 raw, scaled by
  // depth_scale, or CV_32FC1 metres.
  cv::Mat mask(const Features& f, const FrameGeometry& g, const std::vector<uint8_t>& dynamic,
               const std::vector<ObjectBox>* boxes, const std::vector<float>& moving_share,
               const cv::Mat& depth, double depth_scale) const;
  // A late answer's boxes' evidence of moving: the keyframe's own geometric verdicts in each.
  std::vector<float> lateMovingShare(const KeyFrame& kf, const std::vector<ObjectBox>& boxes) const;
  const MovingProbabilityOptions& bayes() const { return bayes_; }

 private:
  std::vector<int8_t> boxObservation(const Features& f, const std::vector<ObjectBox>& boxes,
                                     const std::vector<float>& moving_share) const;
  // The region test (paper section 3.2) per keypoint, with the boxes' moving regions already found: 1 inside
  // a region (at its depth when refined) and not vetoed by a low-dynamic box.
  static std::vector<int8_t> regionObservation(const Features& f, const std::vector<ObjectBox>& boxes,
                                               const std::vector<MovingRegion>& regions);
  // Keypoint i's prior (posterior_before, carried) updated by this frame's box observation, if any.
  void observeBoxes(Frame& frame, int i, double posterior_before) const;
  void observeGeometry(Frame& frame, int i, bool moved) const;
  void observeTracks(Frame& frame, const FrameGeometry& g, const Frame& last,
                     std::vector<int8_t>& verdict) const;
  // Per keypoint matched to no map point, its last-frame keypoint (keypoint_tracks.hpp), or -1.
  std::vector<int> tracksToLast(const Frame& frame, const FrameGeometry& g, const Frame& last) const;
  // Keypoint i's prior is its last-frame keypoint's posterior (carried), updated by this frame's boxes.
  void takeTrackPrior(Frame& frame, int i, double last_posterior) const;
  void observeMovingClusters(Frame& frame, const FrameGeometry& g, const std::vector<int8_t>& verdict) const;
  // Whether keypoint i lies beyond the geometric limit from where p_world projects under the frame's pose.
  bool movedAgainstPose(const Frame& frame, const FrameGeometry& g, int i,
                        const Eigen::Vector3d& p_world) const;
  // kGeometric, an unmatched keypoint: the mean posterior of matched neighbours at its depth (else 0.5),
  // from the frame's matched keypoints bucketed by matchedNeighbours().
  KeypointWindowGrid matchedNeighbours(const Frame& frame, const FrameGeometry& g) const;
  float neighbourPrior(const Frame& frame, const KeypointWindowGrid& matched, int i) const;
  float clampProbability(double p) const;
  // mask(): the region of each cluster of the keypoints `dynamic` flags, marked on m.
  void maskDynamicClusters(const Features& f, const FrameGeometry& g, const std::vector<uint8_t>& dynamic,
                           const cv::Mat& depth, double depth_scale, cv::Mat& m) const;
  // A prior carried from an earlier frame: with kGeometric, what was static may have started to move
  // since (and the reverse), with probability geo_transition; else unchanged, as in the paper.
  double carried(double p) const;

  DynamicOptions options_;
  PoseOptimizerOptions pose_;
  MovingProbabilityOptions bayes_;
  MovingProbabilityOptions geometric_;
};

}  // namespace bmp::tracker

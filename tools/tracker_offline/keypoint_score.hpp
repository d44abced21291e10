#pragma once
// The dynamic stage scored against the truth: each keypoint is on a mover or on the static scene (a mask,
// nonzero on movers), and the stage kept it out or not.
#include <optional>
#include <string>

#include <opencv2/core.hpp>

#include "tracker/tracker.hpp"

namespace bmp::tracker {

class KeypointScore {
 public:
  // Counts the result's keypoints against `movers` (CV_8UC1, nonzero on movers, the image's size); keypoints
  // outside the image are not counted.
  void add(const TrackResult& result, const cv::Mat& movers);

  long onMovers() const { return mover_; }
  long onStatic() const { return static_; }
  long flagged() const { return mover_out_ + static_out_; }
  long moversOut() const { return mover_out_; }
  // Each share is empty when nothing was counted for it (0 / 0): no score, neither perfect nor zero.
  // Of the keypoints kept out, the share on movers.
  std::optional<double> precision() const;
  // Of the keypoints on movers, the share kept out.
  std::optional<double> recall() const;
  // Of the keypoints on the static scene, the share kept out: background lost to the pose.
  std::optional<double> staticKeptOut() const;
  // Of the pose inliers, the share on movers.
  std::optional<double> moversInPoseShare() const;
  // Why: keypoints on movers not kept out, by the region test's verdict in their frame (outside every
  // moving region, or inside one but held below the threshold by their history); static keypoints kept
  // out, inside a moving region or by their history alone.
  long missedOutsideRegions() const { return missed_outside_; }
  long missedInsideRegions() const { return mover_ - mover_out_ - missed_outside_; }
  long staticOutInsideRegions() const { return static_out_in_region_; }
  long staticOutByHistory() const { return static_out_ - static_out_in_region_; }
  // Pose inliers (empty flags: none counted), and those of them on movers: what pulls the camera along.
  long inPose() const { return in_pose_; }
  long moversInPose() const { return mover_in_pose_; }

 private:
  long mover_ = 0, mover_out_ = 0, static_ = 0, static_out_ = 0;
  long missed_outside_ = 0, static_out_in_region_ = 0;
  long in_pose_ = 0, mover_in_pose_ = 0;
};

// The keyframes' dynamic masks (what the mapper leaves out) scored against the truth, pixel by pixel: of
// the movers' pixels the share masked (a mover's pixels left unmasked become ghosts in the map), of the
// static pixels the share masked (static scene the map loses in that keyframe).
class MaskPixelScore {
 public:
  // mask: the keyframe's (CV_8UC1, nonzero masked); movers: the truth's, the same size.
  void add(const cv::Mat& mask, const cv::Mat& movers);
  long keyframes() const { return keyframes_; }
  std::optional<double> moversMasked() const;
  std::optional<double> staticMasked() const;

 private:
  long keyframes_ = 0, mover_ = 0, mover_masked_ = 0, static_ = 0, static_masked_ = 0;
};

// A share as printed: four decimals, or "n/a" when it is undefined.
std::string shareText(const std::optional<double>& share);

}  // namespace bmp::tracker

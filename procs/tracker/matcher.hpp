#pragma once
// Descriptor matching between frames, keyframes and map points: by projection (a predicted position, a
// search window scaled with the pyramid level, Hamming distance, ratio and rotation-consistency checks)
// and by descriptors alone (when no pose prediction can be trusted).
#include <memory>
#include <vector>

#include "tracker/frame.hpp"
#include "tracker/key_frame.hpp"
#include "tracker/map.hpp"
#include "tracker/map_point.hpp"

namespace bmp::tracker {

// The closest and second-closest descriptor among candidates offered one at a time: what every
// ratio-tested search below keeps. Distances are Hamming, at most 256.
struct ClosestTwo {
  int best = -1;  // the closest candidate's index, -1 while none was offered
  int best_dist = 256, second_dist = 256;
  void offer(int index, int d) {
    if (d < best_dist) {
      second_dist = best_dist;
      best_dist = d;
      best = index;
    } else if (d < second_dist) {
      second_dist = d;
    }
  }
};

// Projects the last frame's matched points into `current` (whose pose is the prediction) and matches them
// within radius * scale(level) pixels. Returns the number of new matches.
int matchFromLastFrame(Frame& current, const Frame& last, const FrameGeometry& g, const TrackingOptions& o,
                       double radius);

// Projects map points not yet matched in `current` and matches those inside the view frustum. Counts each
// point seen in the frustum as visible. Returns the number of new matches.
int matchLocalPoints(Frame& current, const std::vector<std::shared_ptr<MapPoint>>& points,
                     const FrameGeometry& g, const TrackingOptions& o, const MatcherOptions& m,
                     double radius);

// Pose-free matching: for each point, the frame keypoint with the closest descriptor, accepted under
// `max_distance` and the ratio test; each keypoint keeps its best point. Fills empty slots of `matches`
// (sized like the features). Returns the number of matches made.
int matchByDescriptors(const Features& features, const std::vector<std::shared_ptr<MapPoint>>& points,
                       double ratio, int max_distance, std::vector<std::shared_ptr<MapPoint>>& matches);

// Projects points into kf: an unobserved keypoint gains the observation, an observed one is merged with
// the point (the one with fewer observations is replaced). A keypoint kf saw as dynamic takes no point:
// its observation would join the point's in local BA (the paper keeps such keypoints out of the map).
// Returns merges + new observations.
int fusePoints(Map& map, KeyFrame* kf, const std::vector<std::shared_ptr<MapPoint>>& points,
               const FrameGeometry& g, const MatcherOptions& m, double radius, double chi2);

// Keypoints of kf1 and kf2 without map points whose descriptors agree and which lie near each other's
// epipolar line (squared pixel distance under epipolar_chi2 times the level's sigma^2). Returns index
// pairs (kf1, kf2).
std::vector<std::pair<int, int>> matchForTriangulation(const KeyFrame& kf1, const KeyFrame& kf2,
                                                       const FrameGeometry& g, int max_distance, double ratio,
                                                       double epipolar_chi2);

}  // namespace bmp::tracker

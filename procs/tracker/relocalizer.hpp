#pragma once
// Relocalisation after loss, without a vocabulary: rank keyframes by how many of a sample of the frame's
// descriptors find a close match among their map points, then for the best few match descriptors,
// solve PnP with RANSAC, refine the pose, and grow the matches by projecting the keyframe's neighbourhood.
#include <memory>

#include "tracker/dynamic_stage.hpp"
#include "tracker/frame.hpp"
#include "tracker/map.hpp"
#include "tracker/tracker_options.hpp"

namespace bmp::tracker {

// On success sets the frame's pose and matches and returns the keyframe it was found against. Each pose
// solve first takes the matched points' moving probabilities (dynamic.applyPriors), so a mover's points
// take no part in it, as in tracking. The caller holds the map lock.
std::shared_ptr<KeyFrame> relocalize(Frame& frame, const Map& map, const FrameGeometry& g,
                                     const TrackerConfig& config, const DynamicStage& dynamic);

}  // namespace bmp::tracker

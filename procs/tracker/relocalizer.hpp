#pragma once
// Relocalisation after loss, without a vocabulary: rank keyframes by how many of a sample of the frame's
// descriptors find a close match among their map points, then for the best few match descriptors,
// solve PnP with RANSAC, refine the pose, and grow the matches by projecting the keyframe's neighbourhood.
#include <memory>

#include "tracker/frame.hpp"
#include "tracker/map.hpp"
#include "tracker/tracker_options.hpp"

namespace bmp::tracker {

// On success sets the frame's pose and matches and returns the keyframe it was found against.
// The caller holds the map lock.
std::shared_ptr<KeyFrame> relocalize(Frame& frame, const Map& map, const FrameGeometry& g,
                                     const TrackerConfig& config);

}  // namespace bmp::tracker

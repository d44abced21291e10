#pragma once
// Paper section 3.4, one keyframe: its static pixels back-projected into a coloured cloud in its camera
// frame.
#include <opencv2/core.hpp>

#include "mapper/keyframe_input.hpp"
#include "mapper/mapper_settings.hpp"
#include "mapper/point_types.hpp"
#include "mapper/ray_table.hpp"

namespace bmp::mapper {

// The mask grown by `margin` pixels (a disc), so the rim of a mover the detector's mask missed goes too.
cv::Mat dilateMask(const cv::Mat& mask, int margin);

// Every `pixel_step`-th pixel with depth in [min, max] metres that the dilated mask leaves, in the camera
// frame (z forward), coloured. Not yet voxel-filtered. kf must pass checkKeyframe; rays must fit its camera.
PointList backProject(const KeyframeInput& kf, const RayTable& rays, const CloudSettings& settings);

}  // namespace bmp::mapper

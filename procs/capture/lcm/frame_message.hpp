#pragma once
// A captured frame as the RGBD_FRAME message (shared by bmp-capture and tum2lcm).
#include <bmp/rgbd_frame_t.hpp>

#include "capture/frame_source.hpp"

namespace bmp::capture {

// Moves the image bytes into the message; frame is left without them.
rgbd_frame_t toFrameMessage(CapturedFrame&& frame, int64_t seq, const CameraIntrinsics& camera,
                            const std::string& source);

}  // namespace bmp::capture

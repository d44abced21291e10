#include "capture/lcm/frame_message.hpp"

#include "bmp/common/stamp.hpp"
#include "bmp/lcm/conversions.hpp"

namespace bmp::capture {

rgbd_frame_t toFrameMessage(CapturedFrame&& frame, int64_t seq, const CameraIntrinsics& camera,
                            const std::string& source) {
  rgbd_frame_t msg;
  msg.utime = secondsToUtime(frame.stamp);
  msg.seq = seq;
  msg.depth_utime = secondsToUtime(frame.depth_stamp);
  msg.source = source;
  msg.camera = toMsg(camera);
  msg.depth_scale = camera.depth_scale;
  msg.color = toMsg(std::move(frame.color));
  msg.depth = toMsg(std::move(frame.depth));
  return msg;
}

}  // namespace bmp::capture

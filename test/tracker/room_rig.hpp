#pragma once
// The tracker's front end on a scene built from a real TUM frame: the default camera (525, 319.5, 239.5,
// no distortion) and configuration, and the frame's keypoints with a depth image the test draws.
#include <string>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "shared_data.hpp"
#include "tracker/frame.hpp"
#include "tracker/orb_extractor.hpp"

namespace bmp::tracker::test_rig {

// A TUM fr3 frame of a room with people, grey, 640x480; empty when ../shared is missing.
inline cv::Mat loadRoom() {
  cv::Mat room =
      cv::imread(test::sharedPath("images/tum_fr3_sitting_xyz_1341845839.214000.png"), cv::IMREAD_GRAYSCALE);
  if (!room.empty()) cv::resize(room, room, cv::Size(640, 480));
  return room;
}

// Whether p lies inside r shrunk by inset pixels on every side (a negative inset grows it): a keypoint well
// inside a drawn region is surely on it, one well outside surely off it.
inline bool insideBy(const cv::Rect& r, const cv::Point2f& p, int inset) {
  return p.x >= r.x + inset && p.y >= r.y + inset && p.x < r.x + r.width - inset &&
         p.y < r.y + r.height - inset;
}

struct RoomRig {
  CameraIntrinsics k;
  TrackerConfig config;
  FrameGeometry g{k, config};
  OrbExtractor extractor{config.orb};
  // A frame of seq at 30 Hz with the camera at the origin.
  Frame frame(int seq, const cv::Mat& gray, const cv::Mat& depth) const {
    Frame f(seq, seq / 30.0, buildFeatures(extractor.extract(gray), depth, g, nullptr, cv::Mat()));
    f.setPose(SE3::Identity());
    return f;
  }
};

}  // namespace bmp::tracker::test_rig

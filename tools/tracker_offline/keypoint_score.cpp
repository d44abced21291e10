#include "tracker_offline/keypoint_score.hpp"

#include <cstdio>
#include <stdexcept>

namespace bmp::tracker {

namespace {
std::optional<double> share(long part, long whole) {
  if (whole <= 0) return std::nullopt;
  return static_cast<double>(part) / static_cast<double>(whole);
}
}  // namespace

void KeypointScore::add(const TrackResult& result, const cv::Mat& movers) {
  if (movers.type() != CV_8UC1) throw std::invalid_argument("KeypointScore: the mover mask must be CV_8UC1");
  if (result.keypoint_dynamic.size() != result.keypoints.size())
    throw std::invalid_argument("KeypointScore: keypoints and their dynamic flags differ in number");
  const bool regions = !result.keypoint_in_region.empty();
  if (regions && result.keypoint_in_region.size() != result.keypoints.size())
    throw std::invalid_argument("KeypointScore: keypoints and their region verdicts differ in number");
  const bool pose = !result.keypoint_in_pose.empty();
  if (pose && result.keypoint_in_pose.size() != result.keypoints.size())
    throw std::invalid_argument("KeypointScore: keypoints and their pose flags differ in number");
  for (std::size_t k = 0; k < result.keypoints.size(); ++k) {
    const cv::Point p(cvRound(result.keypoints[k].x), cvRound(result.keypoints[k].y));
    if (p.x < 0 || p.y < 0 || p.x >= movers.cols || p.y >= movers.rows) continue;
    const bool out = result.keypoint_dynamic[k] != 0;
    const bool in_region = regions && result.keypoint_in_region[k] != 0;
    const bool in_pose = pose && result.keypoint_in_pose[k] != 0;
    in_pose_ += in_pose;
    if (movers.at<uint8_t>(p) != 0) {
      ++mover_;
      mover_in_pose_ += in_pose;
      mover_out_ += out;
      missed_outside_ += !out && !in_region;
    } else {
      ++static_;
      static_out_ += out;
      static_out_in_region_ += out && in_region;
    }
  }
}

std::optional<double> KeypointScore::precision() const {
  return share(mover_out_, mover_out_ + static_out_);
}
std::optional<double> KeypointScore::recall() const {
  return share(mover_out_, mover_);
}
std::optional<double> KeypointScore::staticKeptOut() const {
  return share(static_out_, static_);
}
std::optional<double> KeypointScore::moversInPoseShare() const {
  return share(mover_in_pose_, in_pose_);
}

void MaskPixelScore::add(const cv::Mat& mask, const cv::Mat& movers) {
  if (mask.type() != CV_8UC1 || movers.type() != CV_8UC1 || mask.size() != movers.size())
    throw std::invalid_argument("MaskPixelScore: the masks must be CV_8UC1 and of one size");
  const long on_movers = cv::countNonZero(movers);
  const long masked_movers = cv::countNonZero(mask & movers);
  ++keyframes_;
  mover_ += on_movers;
  mover_masked_ += masked_movers;
  static_ += static_cast<long>(mask.total()) - on_movers;
  static_masked_ += cv::countNonZero(mask) - masked_movers;
}

std::optional<double> MaskPixelScore::moversMasked() const {
  return share(mover_masked_, mover_);
}
std::optional<double> MaskPixelScore::staticMasked() const {
  return share(static_masked_, static_);
}

std::string shareText(const std::optional<double>& share) {
  if (!share) return "n/a";
  char text[32];
  std::snprintf(text, sizeof(text), "%.4f", *share);
  return text;
}

}  // namespace bmp::tracker

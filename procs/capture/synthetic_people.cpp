#include "capture/synthetic_people.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "bmp/common/shared_paths.hpp"

namespace bmp::capture::synth {
namespace {

// GrabCut works on a reduced copy: a few hundred pixels tall is plenty for a silhouette and keeps scene
// construction fast.
constexpr int kSegmentationHeight = 240;
constexpr int kGrabCutIterations = 5;

// GrabCut seeds its colour models with k-means, which draws from OpenCV's thread-local RNG: pin it for the
// call, so the same photo always gives the same silhouette, and put the caller's state back. Outside the
// box is background; the middle of the upper body of a standing person is certainly the person.
cv::Mat grabCutForeground(const cv::Mat& bgr, const cv::Rect& rect) {
  const cv::RNG saved = cv::theRNG();
  cv::theRNG() = cv::RNG(0x5EEDu);
  cv::Mat labels(bgr.size(), CV_8UC1, cv::Scalar(cv::GC_BGD)), bgd_model, fgd_model;
  labels(rect).setTo(cv::GC_PR_FGD);
  labels(cv::Rect(rect.x + rect.width * 2 / 5, rect.y + rect.height / 6, std::max(1, rect.width / 5),
                  rect.height / 3))
      .setTo(cv::GC_FGD);
  cv::grabCut(bgr, labels, rect, bgd_model, fgd_model, kGrabCutIterations, cv::GC_INIT_WITH_MASK);
  cv::theRNG() = saved;
  return (labels == cv::GC_FGD) | (labels == cv::GC_PR_FGD);
}

// The large 8-connected regions with their small holes filled: GrabCut leaves specks and, in patterned
// clothes, small holes that would show the room through the person. Large holes (between the legs, under
// an arm) are background and stay open.
cv::Mat largestRegion(const cv::Mat& fg) {
  cv::Mat labels, stats, centroids;
  const int n = cv::connectedComponentsWithStats(fg, labels, stats, centroids, 8);
  int best_area = 0;
  for (int i = 1; i < n; ++i) best_area = std::max(best_area, stats.at<int>(i, cv::CC_STAT_AREA));
  // Other large parts stay too: a leg GrabCut separated at the knee is still the person.
  cv::Mat region = cv::Mat::zeros(fg.size(), CV_8UC1);
  for (int i = 1; i < n; ++i)
    if (stats.at<int>(i, cv::CC_STAT_AREA) * 20 >= best_area) region.setTo(255, labels == i);
  const int holes = cv::connectedComponentsWithStats(~region, labels, stats, centroids, 4);
  const int small = std::max(4, best_area / 200);
  for (int i = 1; i < holes; ++i) {
    const int* st = stats.ptr<int>(i);
    const bool inside = st[cv::CC_STAT_LEFT] > 0 && st[cv::CC_STAT_TOP] > 0 &&
                        st[cv::CC_STAT_LEFT] + st[cv::CC_STAT_WIDTH] < fg.cols &&
                        st[cv::CC_STAT_TOP] + st[cv::CC_STAT_HEIGHT] < fg.rows;
    if (inside && st[cv::CC_STAT_AREA] <= small) region.setTo(255, labels == i);
  }
  return region;
}

// The person's silhouette inside rect of image, at full resolution, cropped to rect.
cv::Mat segment(const cv::Mat& image, const cv::Rect& rect) {
  // Some margin around the box gives GrabCut background samples on every side.
  const int pad = std::max(4, rect.height / 10);
  const cv::Rect padded =
      (rect + cv::Size(2 * pad, 2 * pad) - cv::Point(pad, pad)) & cv::Rect(0, 0, image.cols, image.rows);
  const double scale = std::min(1.0, static_cast<double>(kSegmentationHeight) / padded.height);
  cv::Mat small;
  cv::resize(image(padded), small, cv::Size(), scale, scale, cv::INTER_AREA);
  const cv::Rect inner = rect - padded.tl();
  cv::Rect small_rect(cvRound(inner.x * scale), cvRound(inner.y * scale), cvRound(inner.width * scale),
                      cvRound(inner.height * scale));
  small_rect &= cv::Rect(1, 1, small.cols - 2, small.rows - 2);  // GrabCut needs background around it
  cv::Mat fg = largestRegion(grabCutForeground(small, small_rect));
  cv::Mat full;
  cv::resize(fg, full, padded.size(), 0, 0, cv::INTER_LINEAR);
  return cv::Mat(full(inner) > 127);
}

}  // namespace

PersonCutout cutOutPerson(const PersonSource& source) {
  const std::string path = resolveSharedPath(source.image);
  const cv::Mat image = cv::imread(path, cv::IMREAD_COLOR);
  if (image.empty()) throw std::runtime_error("synthetic scene: cannot read person image " + path);
  const cv::Rect rect(source.rect[0], source.rect[1], source.rect[2], source.rect[3]);
  if (rect.width < 16 || rect.height < 32 || (rect & cv::Rect(0, 0, image.cols, image.rows)) != rect)
    throw std::runtime_error("synthetic scene: person box [" + std::to_string(rect.x) + ", " +
                             std::to_string(rect.y) + ", " + std::to_string(rect.width) + ", " +
                             std::to_string(rect.height) + "] is too small or outside " + path);
  PersonCutout out;
  out.alpha = segment(image, rect);
  if (cv::countNonZero(out.alpha) < rect.area() / 10)
    throw std::runtime_error("synthetic scene: no person found in the box of " + path);
  out.bgr = image(rect).clone();
  out.bgr.setTo(cv::mean(out.bgr, out.alpha), ~out.alpha);
  cv::flip(out.bgr, out.bgr, 0);  // row 0 at the feet
  cv::flip(out.alpha, out.alpha, 0);
  out.height_m = source.height_m;
  out.texels_per_metre = rect.height / source.height_m;
  out.width_m = rect.width / out.texels_per_metre;
  return out;
}

PersonCutout mirrored(const PersonCutout& cutout) {
  PersonCutout out = cutout;
  cv::flip(cutout.bgr, out.bgr, 1);
  cv::flip(cutout.alpha, out.alpha, 1);
  return out;
}

}  // namespace bmp::capture::synth

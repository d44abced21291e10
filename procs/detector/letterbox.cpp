#include "detector/letterbox.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

namespace bmp::detector {

LetterboxTransform letterbox(const cv::Mat& bgr, int size, cv::Mat& square) {
  if (bgr.empty() || bgr.type() != CV_8UC3) throw std::invalid_argument("letterbox needs a CV_8UC3 image");
  if (size <= 0) throw std::invalid_argument("letterbox size must be positive");
  LetterboxTransform t;
  t.scale = std::min(static_cast<float>(size) / bgr.cols, static_cast<float>(size) / bgr.rows);
  const int width = std::clamp(static_cast<int>(std::lround(bgr.cols * t.scale)), 1, size);
  const int height = std::clamp(static_cast<int>(std::lround(bgr.rows * t.scale)), 1, size);
  t.pad_x = (size - width) / 2;
  t.pad_y = (size - height) / 2;
  square.create(size, size, CV_8UC3);
  square.setTo(cv::Scalar::all(kLetterboxPadValue));
  cv::Mat inner = square(cv::Rect(t.pad_x, t.pad_y, width, height));
  if (width == bgr.cols && height == bgr.rows) {
    bgr.copyTo(inner);
  } else {
    cv::resize(bgr, inner, inner.size(), 0, 0, cv::INTER_LINEAR);
  }
  return t;
}

}  // namespace bmp::detector

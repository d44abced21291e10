#pragma once
// Letterboxing: scale the image so its longer side fits a square network input, keep the aspect ratio,
// and pad the rest with grey (114, as YOLOv5 was trained).
#include <opencv2/core.hpp>

namespace bmp::detector {

struct LetterboxTransform {
  float scale = 1.0f;  // input pixels per image pixel
  int pad_x = 0;       // left padding, input pixels
  int pad_y = 0;       // top padding, input pixels

  // A box in network-input pixels -> the same box in original image pixels.
  cv::Rect2f toImage(const cv::Rect2f& box_input) const {
    return {(box_input.x - pad_x) / scale, (box_input.y - pad_y) / scale, box_input.width / scale,
            box_input.height / scale};
  }
};

inline constexpr int kLetterboxPadValue = 114;

// Writes a size x size CV_8UC3 image to square. bgr must be a non-empty CV_8UC3 image.
LetterboxTransform letterbox(const cv::Mat& bgr, int size, cv::Mat& square);

}  // namespace bmp::detector

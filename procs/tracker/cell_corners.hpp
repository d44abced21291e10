#pragma once
// FAST corners of one pyramid level, with the weak threshold only where the strong one finds nothing.
#include <vector>

#include <opencv2/core.hpp>

namespace bmp::tracker {

struct CellCornerOptions {
  int border = 0;         // corners nearer the image edge are dropped
  int cell = 30;          // pixels; cells are counted from the image origin
  int threshold = 20;     // a cell keeps only its corners at least this strong when it has any
  int min_threshold = 7;  // otherwise its corners at least this strong
};

// The same corners, in the same order (row by row, then by column), as FAST with non-maximum suppression at
// min_threshold over the whole image, of which a cell holding a corner of response >= threshold keeps only
// those. FAST runs at the strong threshold over the image and at the weak one only on the weak cells (plus
// the margin its circle and the suppression read): weak corners are most of FAST's work on a textured image.
std::vector<cv::KeyPoint> cellCorners(const cv::Mat& image, const CellCornerOptions& options);

}  // namespace bmp::tracker

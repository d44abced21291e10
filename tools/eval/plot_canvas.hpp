#pragma once
// A minimal 2-D plotting panel on an OpenCV image: data-to-pixel mapping, grid with round tick values,
// axis labels, polylines and a legend. Just enough for bmp-eval's PNGs.
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace bmp::eval {

struct Range {
  double lo = 0.0;
  double hi = 1.0;
  double span() const { return hi - lo; }
};

// A 1, 2 or 5 times a power of ten giving about target_ticks intervals over span.
double niceStep(double span, int target_ticks);
// The range grown by fraction of its span on both sides; a degenerate range gets a unit span.
Range padded(Range r, double fraction);

struct LegendEntry {
  std::string label;
  cv::Scalar color;
  int thickness = 2;  // 0: a start/end marker pair instead of a line
};

class PlotPanel {
 public:
  // area: the inner plotting rectangle in image pixels; axis labels are drawn outside it.
  PlotPanel(cv::Mat& image, cv::Rect area, Range x, Range y);

  cv::Point2d toPixel(double x, double y) const;
  void drawAxes(const std::string& x_label, const std::string& y_label, const std::string& unit_suffix = "");
  void polyline(const std::vector<cv::Point2d>& points, const cv::Scalar& color, int thickness) const;
  void segment(const cv::Point2d& a, const cv::Point2d& b, const cv::Scalar& color, int thickness) const;
  void marker(const cv::Point2d& p, const cv::Scalar& color, int radius, bool filled) const;
  // A dashed horizontal line across the panel with a label at its right end.
  void referenceLine(double y, const cv::Scalar& color, const std::string& label) const;
  // Drawn in the inner corner holding the fewest of avoid (data points), so it hides as little as possible.
  void legend(const std::vector<LegendEntry>& entries, const std::vector<cv::Point2d>& avoid = {}) const;

 private:
  cv::Mat& image_;
  cv::Rect area_;
  Range x_;
  Range y_;
};

// Text helpers in the panel's font.
void putTextCentered(cv::Mat& image, const std::string& text, cv::Point center, double scale, int thickness,
                     const cv::Scalar& color = cv::Scalar(30, 30, 30));
void putTextVertical(cv::Mat& image, const std::string& text, cv::Point center, double scale,
                     const cv::Scalar& color = cv::Scalar(30, 30, 30));

// Writes the image as PNG; throws EvalError naming the path when it cannot.
void savePlot(const std::string& path, const cv::Mat& image);

}  // namespace bmp::eval

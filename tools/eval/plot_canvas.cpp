#include "eval/plot_canvas.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "eval/eval_error.hpp"

namespace bmp::eval {

namespace {
constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;
constexpr int kShift = 4;  // sub-pixel bits for smooth anti-aliased lines
constexpr double kShiftScale = 1 << kShift;
const cv::Scalar kText(30, 30, 30);
const cv::Scalar kGrid(225, 225, 225);
const cv::Scalar kAxis(90, 90, 90);

cv::Point fixedPoint(const cv::Point2d& p) {
  return {static_cast<int>(std::lround(p.x * kShiftScale)), static_cast<int>(std::lround(p.y * kShiftScale))};
}

std::string tickLabel(double value, double step) {
  const int digits = step >= 1.0 ? 0 : static_cast<int>(std::ceil(-std::log10(step) - 1e-9));
  if (std::abs(value) < step * 1e-6) value = 0.0;  // no "-0.0"
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.*f", digits, value);
  return buffer;
}
}  // namespace

double niceStep(double span, int target_ticks) {
  if (!(span > 0)) return 1.0;
  const double raw = span / std::max(1, target_ticks);
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0}) {
    if (m * power >= raw) return m * power;
  }
  return 10.0 * power;
}

Range padded(Range r, double fraction) {
  if (!(r.span() > 1e-12)) return {r.lo - 0.5, r.hi + 0.5};
  const double pad = r.span() * fraction;
  return {r.lo - pad, r.hi + pad};
}

PlotPanel::PlotPanel(cv::Mat& image, cv::Rect area, Range x, Range y)
    : image_(image), area_(area), x_(x), y_(y) {}

cv::Point2d PlotPanel::toPixel(double x, double y) const {
  return {area_.x + (x - x_.lo) / x_.span() * area_.width, area_.y + (y_.hi - y) / y_.span() * area_.height};
}

void PlotPanel::drawAxes(const std::string& x_label, const std::string& y_label,
                         const std::string& unit_suffix) {
  const double x_step = niceStep(x_.span(), std::max(2, area_.width / 110));
  const double y_step = niceStep(y_.span(), std::max(2, area_.height / 70));
  for (double v = std::ceil(x_.lo / x_step) * x_step; v <= x_.hi + 1e-9 * x_step; v += x_step) {
    const int px = static_cast<int>(std::lround(toPixel(v, 0).x));
    cv::line(image_, {px, area_.y}, {px, area_.y + area_.height}, kGrid, 1);
    cv::line(image_, {px, area_.y + area_.height}, {px, area_.y + area_.height + 5}, kAxis, 1);
    putTextCentered(image_, tickLabel(v, x_step) + unit_suffix, {px, area_.y + area_.height + 20}, 0.45, 1);
  }
  for (double v = std::ceil(y_.lo / y_step) * y_step; v <= y_.hi + 1e-9 * y_step; v += y_step) {
    const int py = static_cast<int>(std::lround(toPixel(0, v).y));
    cv::line(image_, {area_.x, py}, {area_.x + area_.width, py}, kGrid, 1);
    cv::line(image_, {area_.x - 5, py}, {area_.x, py}, kAxis, 1);
    const std::string text = tickLabel(v, y_step) + unit_suffix;
    int baseline = 0;
    const cv::Size size = cv::getTextSize(text, kFont, 0.45, 1, &baseline);
    cv::putText(image_, text, {area_.x - 9 - size.width, py + size.height / 2}, kFont, 0.45, kText, 1,
                cv::LINE_AA);
  }
  cv::rectangle(image_, area_, kAxis, 1);
  putTextCentered(image_, x_label, {area_.x + area_.width / 2, area_.y + area_.height + 48}, 0.55, 1);
  putTextVertical(image_, y_label, {std::max(12, area_.x - 70), area_.y + area_.height / 2}, 0.55);
}

void PlotPanel::polyline(const std::vector<cv::Point2d>& points, const cv::Scalar& color,
                         int thickness) const {
  if (points.size() < 2) return;
  std::vector<cv::Point> pixels;
  pixels.reserve(points.size());
  for (const auto& p : points) pixels.push_back(fixedPoint(toPixel(p.x, p.y)));
  cv::Mat roi = image_;
  cv::polylines(roi, std::vector<std::vector<cv::Point>>{pixels}, false, color, thickness, cv::LINE_AA,
                kShift);
}

void PlotPanel::segment(const cv::Point2d& a, const cv::Point2d& b, const cv::Scalar& color,
                        int thickness) const {
  cv::line(image_, fixedPoint(toPixel(a.x, a.y)), fixedPoint(toPixel(b.x, b.y)), color, thickness,
           cv::LINE_AA, kShift);
}

void PlotPanel::marker(const cv::Point2d& p, const cv::Scalar& color, int radius, bool filled) const {
  cv::circle(image_, fixedPoint(toPixel(p.x, p.y)), radius * static_cast<int>(kShiftScale), color,
             filled ? cv::FILLED : 2, cv::LINE_AA, kShift);
}

void PlotPanel::referenceLine(double y, const cv::Scalar& color, const std::string& label) const {
  const double py = toPixel(0, y).y;
  for (double x = area_.x; x < area_.x + area_.width; x += 14) {
    const double x_end = std::min<double>(x + 8, area_.x + area_.width);
    cv::line(image_, fixedPoint({x, py}), fixedPoint({x_end, py}), color, 1, cv::LINE_AA, kShift);
  }
  int baseline = 0;
  const cv::Size size = cv::getTextSize(label, kFont, 0.45, 1, &baseline);
  const cv::Point org(area_.x + area_.width - size.width - 6, static_cast<int>(py) - 6);
  cv::rectangle(image_, {org.x - 3, org.y - size.height - 3}, {org.x + size.width + 3, org.y + baseline},
                cv::Scalar(255, 255, 255), cv::FILLED);
  cv::putText(image_, label, org, kFont, 0.45, color, 1, cv::LINE_AA);
}

void PlotPanel::legend(const std::vector<LegendEntry>& entries, const std::vector<cv::Point2d>& avoid) const {
  int width = 0;
  int baseline = 0;
  for (const auto& e : entries)
    width = std::max(width, cv::getTextSize(e.label, kFont, 0.5, 1, &baseline).width);
  const int row = 24;
  const cv::Size size(width + 60, row * static_cast<int>(entries.size()) + 10);
  const int left = area_.x + 12;
  const int right = area_.x + area_.width - 12 - size.width;
  const int top = area_.y + 12;
  const int bottom = area_.y + area_.height - 12 - size.height;
  cv::Rect box(cv::Point(left, top), size);
  int fewest = -1;
  for (const cv::Point corner :
       {cv::Point(left, top), cv::Point(right, top), cv::Point(left, bottom), cv::Point(right, bottom)}) {
    const cv::Rect candidate(corner, size);
    int hidden = 0;
    for (const auto& p : avoid) {
      const cv::Point2d px = toPixel(p.x, p.y);
      if (candidate.contains(cv::Point(static_cast<int>(px.x), static_cast<int>(px.y)))) ++hidden;
    }
    if (fewest < 0 || hidden < fewest) {
      fewest = hidden;
      box = candidate;
    }
  }
  cv::rectangle(image_, box, cv::Scalar(255, 255, 255), cv::FILLED);
  cv::rectangle(image_, box, cv::Scalar(170, 170, 170), 1);
  for (std::size_t k = 0; k < entries.size(); ++k) {
    const int y = box.y + 17 + row * static_cast<int>(k);
    if (entries[k].thickness > 0) {
      cv::line(image_, {box.x + 10, y}, {box.x + 40, y}, entries[k].color, entries[k].thickness, cv::LINE_AA);
    } else {  // a marker entry: filled dot and ring
      cv::circle(image_, {box.x + 16, y}, 6, entries[k].color, cv::FILLED, cv::LINE_AA);
      cv::circle(image_, {box.x + 34, y}, 6, entries[k].color, 2, cv::LINE_AA);
    }
    cv::putText(image_, entries[k].label, {box.x + 48, y + 5}, kFont, 0.5, kText, 1, cv::LINE_AA);
  }
}

void putTextCentered(cv::Mat& image, const std::string& text, cv::Point center, double scale, int thickness,
                     const cv::Scalar& color) {
  int baseline = 0;
  const cv::Size size = cv::getTextSize(text, kFont, scale, thickness, &baseline);
  cv::putText(image, text, {center.x - size.width / 2, center.y + size.height / 2}, kFont, scale, color,
              thickness, cv::LINE_AA);
}

void putTextVertical(cv::Mat& image, const std::string& text, cv::Point center, double scale,
                     const cv::Scalar& color) {
  int baseline = 0;
  const cv::Size size = cv::getTextSize(text, kFont, scale, 1, &baseline);
  cv::Mat strip(size.height + baseline + 4, size.width + 4, image.type(), cv::Scalar(255, 255, 255));
  cv::putText(strip, text, {2, size.height + 2}, kFont, scale, color, 1, cv::LINE_AA);
  cv::Mat rotated;
  cv::rotate(strip, rotated, cv::ROTATE_90_COUNTERCLOCKWISE);
  cv::Rect target(center.x - rotated.cols / 2, center.y - rotated.rows / 2, rotated.cols, rotated.rows);
  target &= cv::Rect(0, 0, image.cols, image.rows);
  if (target.area() == 0) return;
  rotated(cv::Rect(0, 0, target.width, target.height)).copyTo(image(target));
}

void savePlot(const std::string& path, const cv::Mat& image) {
  bool ok = false;
  try {
    ok = cv::imwrite(path, image);
  } catch (const cv::Exception&) {
    ok = false;
  }
  if (!ok) throw EvalError(path + ": cannot write plot");
}

}  // namespace bmp::eval

#include "eval/eval_plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <opencv2/imgproc.hpp>

#include "eval/eval_error.hpp"
#include "eval/plot_canvas.hpp"

namespace bmp::eval {

namespace {
// BGR colours.
const cv::Scalar kGtColor(50, 50, 50);
const cv::Scalar kEstColor(190, 110, 20);
const cv::Scalar kLinkColor(150, 150, 240);
const cv::Scalar kAteColor(190, 110, 20);
const cv::Scalar kRpeColor(40, 140, 40);
const cv::Scalar kRmseColor(40, 40, 200);

std::string format(const char* fmt, double v) {
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), fmt, v);
  return buffer;
}

// Grows one range so that both have the same metres per pixel in the given area.
void equalScale(Range& x, Range& y, const cv::Size& area) {
  const double scale = std::max(x.span() / area.width, y.span() / area.height);
  const double xc = 0.5 * (x.lo + x.hi);
  const double yc = 0.5 * (y.lo + y.hi);
  x = {xc - 0.5 * scale * area.width, xc + 0.5 * scale * area.width};
  y = {yc - 0.5 * scale * area.height, yc + 0.5 * scale * area.height};
}
}  // namespace

void plotTrajectoryTopView(const std::string& path, const Trajectory& gt, const Trajectory& aligned_est,
                           const AteResult& ate, const std::string& title) {
  cv::Mat image(960, 1000, CV_8UC3, cv::Scalar(255, 255, 255));
  const cv::Rect area(110, 70, 860, 800);
  std::vector<cv::Point2d> gt_xy;
  std::vector<cv::Point2d> est_xy;
  for (const auto& p : gt)
    gt_xy.emplace_back(p.T_world_cam.translation().x(), p.T_world_cam.translation().y());
  for (const auto& p : aligned_est)
    est_xy.emplace_back(p.T_world_cam.translation().x(), p.T_world_cam.translation().y());
  Range x{1e300, -1e300};
  Range y{1e300, -1e300};
  for (const auto* pts : {&gt_xy, &est_xy}) {
    for (const auto& p : *pts) {
      x = {std::min(x.lo, p.x), std::max(x.hi, p.x)};
      y = {std::min(y.lo, p.y), std::max(y.hi, p.y)};
    }
  }
  x = padded(x, 0.06);
  y = padded(y, 0.06);
  equalScale(x, y, area.size());
  PlotPanel panel(image, area, x, y);
  panel.drawAxes("x [m]", "y [m]");
  for (const auto& pair : ate.pairs) {
    panel.segment({pair.gt_position.x(), pair.gt_position.y()},
                  {pair.aligned_position.x(), pair.aligned_position.y()}, kLinkColor, 1);
  }
  panel.polyline(gt_xy, kGtColor, 2);
  panel.polyline(est_xy, kEstColor, 1);
  if (!gt_xy.empty()) {
    panel.marker(gt_xy.front(), kGtColor, 6, true);
    panel.marker(gt_xy.back(), kGtColor, 6, false);
  }
  panel.legend({{"ground truth", kGtColor, 2},
                {"estimate (aligned)", kEstColor, 1},
                {"associated pairs", kLinkColor, 1},
                {"start (filled) / end (ring)", kGtColor, 0}},
               [&] {
                 std::vector<cv::Point2d> all = gt_xy;
                 all.insert(all.end(), est_xy.begin(), est_xy.end());
                 return all;
               }());
  putTextCentered(image, title, {image.cols / 2, 24}, 0.65, 1);
  putTextCentered(image,
                  "top view (x-y of the ground-truth frame)   ATE rmse " +
                      format("%.2f cm", ate.stats.rmse * 100) + " over " + std::to_string(ate.stats.count) +
                      " pairs",
                  {image.cols / 2, 50}, 0.5, 1);
  savePlot(path, image);
}

void plotErrorsOverTime(const std::string& path, const AteResult& ate, const RpeResult& rpe, double t0,
                        const std::string& rpe_caption, const std::string& title) {
  cv::Mat image(900, 1200, CV_8UC3, cv::Scalar(255, 255, 255));
  const cv::Rect top(110, 70, 1050, 320);
  const cv::Rect bottom(110, 500, 1050, 320);

  Range t{1e300, -1e300};
  std::vector<cv::Point2d> ate_pts;
  for (const auto& p : ate.pairs) ate_pts.emplace_back(p.gt_stamp - t0, p.error);
  std::vector<cv::Point2d> rpe_pts;
  for (const auto& p : rpe.pairs) rpe_pts.emplace_back(p.est_stamp_0 - t0, p.trans_error);
  for (const auto* pts : {&ate_pts, &rpe_pts}) {
    for (const auto& p : *pts) t = {std::min(t.lo, p.x), std::max(t.hi, p.x)};
  }
  if (t.lo > t.hi) t = {0, 1};
  t = padded(t, 0.01);

  auto panel_for = [&](const cv::Rect& area, const std::vector<cv::Point2d>& pts, const ErrorStats& stats,
                       const cv::Scalar& color, const std::string& y_label, const std::string& heading) {
    double y_max = 0;
    for (const auto& p : pts) y_max = std::max(y_max, p.y);
    if (!(y_max > 0)) y_max = 1e-3;
    PlotPanel panel(image, area, t, {0.0, y_max * 1.1});
    panel.drawAxes("time since first ground-truth stamp [s]", y_label);
    panel.polyline(pts, color, 1);
    if (pts.size() == 1) panel.marker(pts.front(), color, 3, true);
    if (stats.count > 0)
      panel.referenceLine(stats.rmse, kRmseColor, "rmse " + format("%.2f cm", stats.rmse * 100));
    putTextCentered(image, heading, {area.x + area.width / 2, area.y - 16}, 0.55, 1);
    if (pts.empty()) {
      putTextCentered(image, "no pairs", {area.x + area.width / 2, area.y + area.height / 2}, 0.7, 1);
    }
  };
  panel_for(top, ate_pts, ate.stats, kAteColor, "ATE [m]",
            "absolute trajectory error per associated pair (" + std::to_string(ate.stats.count) + " pairs)");
  panel_for(bottom, rpe_pts, rpe.trans, kRpeColor, "RPE translation [m]",
            "relative pose error, translation, " + rpe_caption + " (" + std::to_string(rpe.trans.count) +
                " pairs)");
  putTextCentered(image, title, {image.cols / 2, 22}, 0.65, 1);
  savePlot(path, image);
}

}  // namespace bmp::eval

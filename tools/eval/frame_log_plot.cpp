#include "eval/frame_log_plot.hpp"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>

#include <opencv2/imgproc.hpp>

#include "bmp/common/timing.hpp"
#include "eval/eval_error.hpp"
#include "eval/plot_canvas.hpp"

namespace bmp::eval {

namespace {

constexpr double kFramePeriodMs = 1000.0 / 30.0;  // a 30 Hz camera's budget per frame

// BGR colours.
const cv::Scalar kTrackedColor(150, 120, 60);
const cv::Scalar kMotionColor(120, 190, 120);
const cv::Scalar kReferenceColor(0, 140, 255);
const cv::Scalar kRelocColor(200, 40, 200);
const cv::Scalar kMissedColor(40, 40, 220);
const cv::Scalar kTimeColor(60, 60, 60);
const cv::Scalar kPeriodColor(40, 40, 200);
const cv::Scalar kStdColor(160, 80, 0);

std::vector<std::string> splitTabs(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream in(line);
  std::string field;
  while (std::getline(in, field, '\t')) out.push_back(field);
  return out;
}

template <typename T>
T parse(const std::string& text, const std::string& where) {
  std::istringstream in(text);
  T value{};
  if (!(in >> value) || !in.eof()) throw EvalError(where + ": '" + text + "' is not a number");
  return value;
}

cv::Scalar sourceColor(const std::string& source) {
  if (source == "reference") return kReferenceColor;
  if (source == "relocalisation") return kRelocColor;
  return kMotionColor;
}

// Each tracked frame's position std: millimetres in an open room, centimetres where the static scene left in
// view is a far band. The scale stops at kStdAxisMaxMm so that one nearly unpinned frame does not flatten
// the rest; those beyond it are drawn at the top.
constexpr double kStdAxisMaxMm = 50.0;

void plotPositionStd(cv::Mat& image, const cv::Rect& area, const Range& t, double t0,
                     const std::vector<FrameLogRow>& rows) {
  TimingStats values;  // not times, but the same median and max as bmp-run's summary and bmp-bench-tracker
  for (const FrameLogRow& r : rows)
    if (r.position_std_mm >= 0.0) values.add(r.position_std_mm);
  const double top = values.empty() ? 10.0 : std::min(kStdAxisMaxMm, values.max());
  PlotPanel panel(image, area, t, {0.0, std::max(top, 1.0) * 1.1});
  panel.drawAxes("time since the first frame [s]", "position std [mm]");
  std::vector<cv::Point2d> line;
  for (const FrameLogRow& r : rows) {
    if (r.position_std_mm < 0.0) continue;
    line.emplace_back(r.stamp - t0, std::min(r.position_std_mm, kStdAxisMaxMm));
  }
  panel.polyline(line, kStdColor, 1);
  std::string heading = "position std per frame (worst direction, from its inliers alone)";
  if (values.empty()) {
    heading += ": not in this log";
  } else {
    char median[64];
    std::snprintf(median, sizeof(median), ", median %.1f mm", values.median());
    heading += median;
  }
  putTextCentered(image, heading, {area.x + area.width / 2, area.y - 16}, 0.55, 1);
}

}  // namespace

std::vector<FrameLogRow> readFrameLog(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw EvalError(path + ": cannot open frame log");
  std::map<std::string, std::size_t> column;
  std::vector<FrameLogRow> rows;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    const std::string where = path + ":" + std::to_string(number);
    if (line.empty()) continue;
    if (line[0] == '#') {
      if (line.rfind("# stamp\t", 0) == 0) {
        const std::vector<std::string> names = splitTabs(line.substr(2));
        for (std::size_t i = 0; i < names.size(); ++i) column[names[i]] = i;
      }
      continue;
    }
    if (column.empty()) throw EvalError(where + ": a frame line before the '# stamp' header");
    const std::vector<std::string> f = splitTabs(line);
    const auto field = [&](const char* name) -> const std::string& {
      const auto it = column.find(name);
      if (it == column.end()) throw EvalError(path + ": the header has no column '" + name + "'");
      if (it->second >= f.size())
        throw EvalError(where + ": " + std::to_string(f.size()) + " fields, no '" + name + "'");
      return f[it->second];
    };
    FrameLogRow r;
    r.stamp = parse<double>(field("stamp"), where);
    r.state = field("state");
    r.tracked = parse<int>(field("tracked"), where);
    r.pose_source = field("pose_source");
    r.first_inliers = parse<int>(field("first_inliers"), where);
    r.frames_missed = parse<int>(field("frames_missed"), where);
    r.track_ms = parse<double>(field("track_ms"), where);
    if (column.count("position_std_mm")) {  // logs from before the column have none
      const std::string& std_mm = field("position_std_mm");
      if (std_mm != "-") r.position_std_mm = parse<double>(std_mm, where);
    }
    rows.push_back(r);
  }
  return rows;
}

void plotFrameLog(const std::string& path, const std::vector<FrameLogRow>& rows, const std::string& title) {
  cv::Mat image(1260, 1200, CV_8UC3, cv::Scalar(255, 255, 255));
  const cv::Rect top(110, 70, 1050, 380);
  const cv::Rect middle(110, 560, 1050, 260);
  const cv::Rect bottom(110, 940, 1050, 260);
  const double t0 = rows.empty() ? 0.0 : rows.front().stamp;
  Range t{0.0, rows.empty() ? 1.0 : std::max(rows.back().stamp - t0, 1e-3)};
  t = padded(t, 0.01);

  int max_inliers = 1;
  double max_ms = kFramePeriodMs;
  int missed = 0, lost = 0, reference = 0;
  for (const FrameLogRow& r : rows) {
    max_inliers = std::max({max_inliers, r.tracked, r.first_inliers});
    max_ms = std::max(max_ms, r.track_ms);
    missed += r.frames_missed;
    lost += r.state == "LOST";
    reference += r.pose_source == "reference";
  }
  PlotPanel inliers(image, top, t, {0.0, max_inliers * 1.1});
  inliers.drawAxes("time since the first frame [s]", "inliers");
  std::vector<cv::Point2d> tracked;
  for (const FrameLogRow& r : rows) tracked.emplace_back(r.stamp - t0, r.tracked);
  for (const FrameLogRow& r : rows) {
    const double x = r.stamp - t0;
    if (r.frames_missed > 0)  // a tick as high as the frames missed, 5 % of the panel each
      inliers.segment({x, 0.0}, {x, max_inliers * 0.05 * std::min(r.frames_missed, 10)}, kMissedColor, 2);
    if (r.state == "LOST") inliers.marker({x, 0.0}, kMissedColor, 4, true);
  }
  inliers.polyline(tracked, kTrackedColor, 1);
  std::vector<cv::Point2d> drawn = tracked;  // the legend goes where it hides fewest of the line and dots
  for (const FrameLogRow& r : rows) {
    if (r.pose_source == "none" || r.pose_source == "map_start") continue;
    const bool notable = r.pose_source != "motion";
    drawn.emplace_back(r.stamp - t0, r.first_inliers);
    inliers.marker(drawn.back(), sourceColor(r.pose_source), notable ? 4 : 1, notable);
  }
  inliers.legend({{"tracked (after the local map)", kTrackedColor, 2},
                  {"first pose: motion model", kMotionColor, 2},
                  {"first pose: reference keyframe", kReferenceColor, 2},
                  {"first pose: relocalisation", kRelocColor, 2},
                  {"frames missed before (tick) / lost (dot)", kMissedColor, 2}},
                 drawn);
  putTextCentered(image,
                  "inliers per frame (" + std::to_string(rows.size()) + " frames, " + std::to_string(missed) +
                      " missed, " + std::to_string(lost) + " lost, " + std::to_string(reference) +
                      " from the reference keyframe)",
                  {top.x + top.width / 2, top.y - 16}, 0.55, 1);

  plotPositionStd(image, middle, t, t0, rows);

  PlotPanel time(image, bottom, t, {0.0, max_ms * 1.1});
  time.drawAxes("time since the first frame [s]", "track [ms]");
  std::vector<cv::Point2d> ms;
  for (const FrameLogRow& r : rows) ms.emplace_back(r.stamp - t0, r.track_ms);
  time.polyline(ms, kTimeColor, 1);
  time.referenceLine(kFramePeriodMs, kPeriodColor, "30 Hz");
  putTextCentered(image, "tracking time per frame", {bottom.x + bottom.width / 2, bottom.y - 16}, 0.55, 1);
  if (rows.empty())
    putTextCentered(image, "no frames", {top.x + top.width / 2, top.y + top.height / 2}, 0.7, 1);
  putTextCentered(image, title, {image.cols / 2, 22}, 0.65, 1);
  savePlot(path, image);
}

}  // namespace bmp::eval

#include "tracker/stand_in_boxes.hpp"

#include <cmath>

namespace bmp::tracker {

std::optional<std::vector<ObjectBox>> standInBoxes(const std::vector<FrameBoxes>& before, int64_t frame_utime,
                                                   const DynamicOptions& options) {
  if (before.empty()) return std::nullopt;
  const double age_s = static_cast<double>(frame_utime - before[0].utime) * 1e-6;
  if (age_s <= 0.0 || age_s > options.stale_box_max_age_s) return std::nullopt;
  std::vector<ObjectBox> boxes = before[0].boxes;
  if (before.size() >= 2 && options.stale_box_motion_iou > 0.0) {
    // A speed measured over a long gap says little about now: only answers as close as the age limit.
    const double dt_s = static_cast<double>(before[0].utime - before[1].utime) * 1e-6;
    if (dt_s <= options.stale_box_max_age_s)
      boxes = movedForAge(std::move(boxes), before[1].boxes, dt_s, age_s, options.stale_box_motion_iou);
  }
  return grownForAge(std::move(boxes), age_s, options.stale_box_growth_px_per_s);
}

std::optional<std::vector<ObjectBox>> laggedStandIn(const std::vector<std::vector<ObjectBox>>& answers,
                                                    const std::vector<double>& stamps_s, std::size_t i,
                                                    std::size_t lag, const DynamicOptions& options) {
  const auto utime = [](double stamp) { return static_cast<int64_t>(std::llround(stamp * 1e6)); };
  std::vector<FrameBoxes> before;
  for (std::size_t back = lag; back <= lag + 1 && back <= i; ++back)
    before.push_back(FrameBoxes{utime(stamps_s[i - back]), true, answers[i - back]});
  return standInBoxes(before, utime(stamps_s[i]), options);
}

}  // namespace bmp::tracker

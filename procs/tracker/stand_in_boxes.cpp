#include "tracker/stand_in_boxes.hpp"

#include "bmp/common/stamp.hpp"

namespace bmp::tracker {

std::optional<std::vector<ObjectBox>> standInBoxes(const std::vector<FrameBoxes>& before, int64_t frame_utime,
                                                   const DynamicOptions& options) {
  if (before.empty()) return std::nullopt;
  const double age_s = utimeToSeconds(frame_utime - before[0].utime);
  if (age_s <= 0.0 || age_s > options.stale_box_max_age_s) return std::nullopt;
  std::vector<ObjectBox> boxes = before[0].boxes;
  if (before.size() >= 2 && options.stale_box_motion_iou > 0.0) {
    // A speed measured over a long gap says little about now: only answers as close as the age limit.
    const double dt_s = utimeToSeconds(before[0].utime - before[1].utime);
    if (dt_s <= options.stale_box_max_age_s)
      boxes = movedForAge(std::move(boxes), before[1].boxes, dt_s, age_s, options.stale_box_motion_iou);
  }
  return grownForAge(std::move(boxes), age_s, options.stale_box_growth_px_per_s);
}

std::optional<std::vector<ObjectBox>> laggedStandIn(const std::vector<std::vector<ObjectBox>>& answers,
                                                    const std::vector<double>& stamps_s, std::size_t i,
                                                    std::size_t lag, const DynamicOptions& options) {
  std::vector<FrameBoxes> before;
  for (std::size_t back = lag; back <= lag + 1 && back <= i; ++back)
    before.push_back(FrameBoxes{secondsToUtime(stamps_s[i - back]), true, answers[i - back]});
  return standInBoxes(before, secondsToUtime(stamps_s[i]), options);
}

}  // namespace bmp::tracker

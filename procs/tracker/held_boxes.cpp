#include "tracker/held_boxes.hpp"

#include "bmp/common/box_overlap.hpp"

namespace bmp::tracker {

namespace {
cv::Point2f centre(const cv::Rect2f& r) {
  return {r.x + r.width * 0.5f, r.y + r.height * 0.5f};
}
}  // namespace

HeldBoxes::HeldBoxes(double hold_s, double partner_iou) : hold_s_(hold_s), partner_iou_(partner_iou) {}

cv::Rect2f HeldBoxes::Held::at(double stamp_s) const {
  const auto dt = static_cast<float>(stamp_s - found_s);
  return {box.box.x + velocity.x * dt, box.box.y + velocity.y * dt, box.box.width, box.box.height};
}

std::optional<std::vector<ObjectBox>> HeldBoxes::complete(const std::optional<std::vector<ObjectBox>>& boxes,
                                                          double stamp_s) {
  if (hold_s_ <= 0.0 || !boxes) return boxes;
  if (stamp_s < last_s_) held_.clear();
  last_s_ = stamp_s;

  // Each found box takes the held box it overlaps most, where that one would be now; each held box is
  // taken once.
  std::vector<bool> taken(held_.size(), false);
  std::vector<Held> found;
  for (const ObjectBox& b : *boxes) {
    if (b.level != DynamicLevel::kHigh) continue;
    int partner = -1;
    double best = partner_iou_;
    for (std::size_t h = 0; h < held_.size(); ++h) {
      if (taken[h] || held_[h].box.class_id != b.class_id) continue;
      const double overlap = iou(held_[h].at(stamp_s), b.box);
      if (overlap >= best) {
        best = overlap;
        partner = static_cast<int>(h);
      }
    }
    Held now{b, stamp_s, {0.0f, 0.0f}, false};
    if (partner >= 0) {
      taken[partner] = true;
      const Held& before = held_[partner];
      const double dt = stamp_s - before.found_s;
      if (dt > 0.0) {
        now.velocity = (centre(b.box) - centre(before.box.box)) * static_cast<float>(1.0 / dt);
        now.moving = true;
      }
    }
    found.push_back(now);
  }

  std::optional<std::vector<ObjectBox>> completed = boxes;
  for (std::size_t h = 0; h < held_.size(); ++h) {
    const Held& missed = held_[h];
    if (taken[h] || !missed.moving || stamp_s - missed.found_s > hold_s_) continue;
    ObjectBox box = missed.box;
    box.box = missed.at(stamp_s);
    completed->push_back(box);
    found.push_back(missed);  // still held, as last found: a held box never refreshes itself
  }
  held_ = std::move(found);
  return completed;
}

}  // namespace bmp::tracker

#include "tracker/dynamic_regions.hpp"

#include "bmp/common/box_overlap.hpp"

namespace bmp::tracker {

namespace {

bool inside(const cv::Rect2f& r, const cv::Point2f& p) {
  return p.x >= r.x && p.y >= r.y && p.x < r.x + r.width && p.y < r.y + r.height;
}

float heldShare(const cv::Rect2f& medium, const std::vector<ObjectBox>& boxes) {
  const float area = medium.area();
  if (area <= 0) return 0.0f;
  float best = 0.0f;
  for (const auto& b : boxes)
    if (b.level == DynamicLevel::kHigh) best = std::max(best, (medium & b.box).area() / area);
  return best;
}

}  // namespace

std::vector<uint8_t> movingBoxes(const std::vector<ObjectBox>& boxes, const RegionOptions& options,
                                 const std::vector<float>& moving_share) {
  std::vector<uint8_t> moving(boxes.size(), 0);
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    const ObjectBox& b = boxes[i];
    if (b.level == DynamicLevel::kHigh) {
      moving[i] = 1;
    } else if (b.level == DynamicLevel::kMedium) {
      const bool held = heldShare(b.box, boxes) >= options.medium_held_overlap;
      const bool seen_moving = i < moving_share.size() && moving_share[i] >= options.medium_moving_keypoints;
      moving[i] = held || seen_moving;
    }
  }
  return moving;
}

std::vector<uint8_t> observeRegions(const std::vector<cv::KeyPoint>& keys,
                                    const std::vector<ObjectBox>& boxes, const std::vector<uint8_t>& moving) {
  std::vector<uint8_t> z(keys.size(), 0);
  for (std::size_t k = 0; k < keys.size(); ++k) {
    bool in_moving = false, in_low = false;
    for (std::size_t i = 0; i < boxes.size(); ++i) {
      if (!inside(boxes[i].box, keys[k].pt)) continue;
      if (boxes[i].level == DynamicLevel::kLow) in_low = true;
      if (i < moving.size() && moving[i]) in_moving = true;
    }
    z[k] = in_moving && !in_low;
  }
  return z;
}

std::vector<float> movedShareInBoxes(const std::vector<cv::KeyPoint>& keys,
                                     const std::vector<ObjectBox>& boxes, const std::vector<int8_t>& verdict,
                                     int min_moved) {
  std::vector<float> share(boxes.size(), 0.0f);
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    int judged = 0, moved = 0;
    for (std::size_t k = 0; k < keys.size() && k < verdict.size(); ++k) {
      if (verdict[k] < 0 || !inside(boxes[i].box, keys[k].pt)) continue;
      ++judged;
      moved += verdict[k] > 0;
    }
    share[i] = moved >= std::max(1, min_moved) ? static_cast<float>(moved) / judged : 0.0f;
  }
  return share;
}

std::vector<ObjectBox> grownForAge(std::vector<ObjectBox> boxes, double age_s, double growth_px_per_s) {
  const auto grow = static_cast<float>(std::max(0.0, age_s) * growth_px_per_s);
  for (ObjectBox& b : boxes) {
    if (b.level == DynamicLevel::kLow) continue;
    b.box = cv::Rect2f(b.box.x - grow, b.box.y - grow, b.box.width + 2 * grow, b.box.height + 2 * grow);
  }
  return boxes;
}

std::vector<ObjectBox> movedForAge(std::vector<ObjectBox> newest, const std::vector<ObjectBox>& before,
                                   double dt_s, double age_s, double min_iou) {
  if (dt_s <= 0.0 || age_s <= 0.0) return newest;
  const auto scale = static_cast<float>(age_s / dt_s);
  for (ObjectBox& b : newest) {
    // Low boxes too: a monitor does not move, but it moves in the image while the camera turns, and its
    // veto must stay on it.
    const ObjectBox* partner = nullptr;
    double best = min_iou;
    for (const ObjectBox& e : before) {
      if (e.class_id != b.class_id) continue;
      const double overlap = iou(b.box, e.box);
      if (overlap >= best) {
        best = overlap;
        partner = &e;
      }
    }
    if (!partner) continue;
    const cv::Point2f shift = ((b.box.tl() + b.box.br()) - (partner->box.tl() + partner->box.br())) * 0.5f;
    b.box.x += shift.x * scale;
    b.box.y += shift.y * scale;
  }
  return newest;
}

}  // namespace bmp::tracker

#include "mapper/pose_update_order.hpp"

#include <utility>

namespace bmp::mapper {

void PoseUpdateOrder::keyframeMapped(int64_t utime) {
  if (utime < newest_keyframe_) newest_.clear();
  newest_keyframe_ = utime;
}

std::vector<PoseUpdate> PoseUpdateOrder::notOlder(std::vector<PoseUpdate> updates, int64_t utime,
                                                  std::vector<std::string>& stale) const {
  if (newest_keyframe_ >= 0 && utime > newest_keyframe_ &&
      utime - newest_keyframe_ > kMaxAheadOfKeyframesUs) {
    for (const auto& u : updates)
      stale.push_back("keyframe " + std::to_string(u.id) + ": stamped " + std::to_string(utime) + " us, " +
                      std::to_string((utime - newest_keyframe_) / 1000000) +
                      " s after the newest keyframe: not this map's");
    return {};
  }
  std::vector<PoseUpdate> out;
  out.reserve(updates.size());
  for (auto& u : updates) {
    const auto it = newest_.find(u.id);
    if (it != newest_.end() && utime < it->second)
      stale.push_back("keyframe " + std::to_string(u.id) + ": stamped " + std::to_string(utime) +
                      " us, older than its pose of " + std::to_string(it->second) + " us");
    else
      out.push_back(std::move(u));
  }
  return out;
}

}  // namespace bmp::mapper

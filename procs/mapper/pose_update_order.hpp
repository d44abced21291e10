#pragma once
// Pose updates may arrive out of order (a replayed log, another publisher): a keyframe's pose from an
// older optimisation must not replace a newer one. Remembers, per keyframe, the stamp of the newest update
// taken; bounded by the keyframes the caller reports as taken.
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include "mapper/mapper.hpp"

namespace bmp::mapper {

class PoseUpdateOrder {
 public:
  // The updates of a message stamped `utime` that are not older than the newest taken for their keyframe;
  // each other one is described in `stale` ("keyframe <id>: ...").
  std::vector<PoseUpdate> notOlder(std::vector<PoseUpdate> updates, int64_t utime,
                                   std::vector<std::string>& stale) const;
  // The keyframe's pose is now the one stamped `utime`.
  void taken(int64_t id, int64_t utime) { newest_[id] = utime; }
  // A new map: no keyframe has a pose yet.
  void clear() { newest_.clear(); }

 private:
  std::unordered_map<int64_t, int64_t> newest_;  // keyframe id -> stamp of its pose, microseconds
};

}  // namespace bmp::mapper

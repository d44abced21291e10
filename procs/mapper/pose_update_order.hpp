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
  // A keyframe stamped `utime` was mapped. One stamped before the newest keyframe means the tracker's time
  // base started again (capture restarted, a log played again): the stamps remembered are of the old one,
  // and every update of the new one would be judged older than them.
  void keyframeMapped(int64_t utime);
  // The updates of a message stamped `utime` that are not older than the newest taken for their keyframe;
  // each other one is described in `stale` ("keyframe <id>: ..."). A message stamped far beyond the newest
  // keyframe (a forged stamp) is refused whole: taken, it would make every real update after it look older.
  std::vector<PoseUpdate> notOlder(std::vector<PoseUpdate> updates, int64_t utime,
                                   std::vector<std::string>& stale) const;
  // The keyframe's pose is now the one stamped `utime`.
  void taken(int64_t id, int64_t utime) { newest_[id] = utime; }
  // A new map: no keyframe has a pose yet.
  void clear() {
    newest_.clear();
    newest_keyframe_ = -1;
  }

  // How far an update's stamp may lie beyond the newest keyframe's: the tracker stamps it with the frame at
  // which the optimisation ended, soon after its keyframe, or after a keyframe held for its boxes.
  static constexpr int64_t kMaxAheadOfKeyframesUs = 60'000'000;

 private:
  std::unordered_map<int64_t, int64_t> newest_;  // keyframe id -> stamp of its pose, microseconds
  int64_t newest_keyframe_ = -1;                 // the newest mapped keyframe's stamp; -1: none yet
};

}  // namespace bmp::mapper

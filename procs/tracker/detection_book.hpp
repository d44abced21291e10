#pragma once
// Where the detector's answers wait for their frames. Detections arrive on their own (another process,
// another thread, any order); the tracker asks for a frame's boxes when it tracks it. The rule:
//   - lockstep (wait > 0): the tracker waits for the frame's answer up to the wait, so every run sees the
//     same boxes;
//   - real time (wait = 0): it never waits; a frame whose answer is not there yet is observed with the
//     newest earlier answer (newestBefore, moved on for its age by the tracker node) or, without one, tracked
//     on the probabilities carried by its matches; an answer that comes later is handed over as late
//     (applied to the keyframe the frame made, if it made one).
// Answers are kept by (seq, stamp): one that names a frame's seq with another stamp (a forged or stale
// answer) is kept apart and never displaces or hides the real one. Once the frame itself is heard
// (frameHeard), answers naming its seq with another stamp are refused and dropped, and a seq not heard yet
// holds at most kMaxPerSeq answers, so a flood of forgeries cannot push the real answers out. An answer for a
// frame that already took one is no news (lockstep capture sent the frame again and the detector answered
// it again): it is not kept, or a keyframe held for its late boxes would take it as late and apply the same
// boxes twice. Bounded: only the `capacity` answers with the highest seq are kept, and as many taken.
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "tracker/dynamic_regions.hpp"

namespace bmp::tracker {

struct FrameBoxes {
  int64_t utime = 0;
  bool usable = true;  // false: the detector skipped the frame (no boxes to trust)
  std::vector<ObjectBox> boxes;
};

class DetectionBook {
 public:
  explicit DetectionBook(std::size_t capacity = 256) : capacity_(capacity) {}

  // Keeps the answer; or says why not (its frame was heard with another stamp, its seq already holds
  // kMaxPerSeq answers, or a different answer for the frame is waiting or was taken: the first stands) and
  // keeps nothing. The same answer again (for a frame capture sent again) is no news: "" and nothing
  // changes, whether the first is still waiting or was taken.
  std::string add(int64_t seq, FrameBoxes boxes);
  // The frame (seq, utime) was received: other stamps for its seq are forgeries from here on.
  void frameHeard(int64_t seq, int64_t utime);
  static constexpr std::size_t kMaxPerSeq = 2;
  // The answer for (seq, utime), waiting up to `wait` for it; nullopt when none came. Taken answers are
  // removed.
  std::optional<FrameBoxes> take(int64_t seq, int64_t utime, std::chrono::milliseconds wait);
  // Copies of the n newest usable answers for frames before seq and at or after min_seq, newest first,
  // whether or not their frames took them: the book remembers the last kRecent usable answers for frames
  // heard (answers for frames still to come may be forged, and would push the real ones out). An answer
  // not yet taken stays in the book for its own frame.
  std::vector<FrameBoxes> newestBefore(int64_t seq, int64_t min_seq, std::size_t n) const;
  static constexpr std::size_t kRecent = 4;
  std::size_t size() const;
  std::size_t capacity() const { return capacity_; }
  int64_t discarded() const;  // answers pushed out unused by newer ones

 private:
  const std::size_t capacity_;
  mutable std::mutex mutex_;
  std::condition_variable arrived_;
  std::map<std::pair<int64_t, int64_t>, FrameBoxes> by_frame_;  // (seq, utime)
  std::map<std::pair<int64_t, int64_t>, FrameBoxes> recent_;    // the newest usable answers, taken or not
  std::map<std::pair<int64_t, int64_t>, FrameBoxes> taken_;     // the newest answers taken, as taken
  std::map<int64_t, int64_t> heard_;                            // seq -> stamp of the newest frames heard
  int64_t discarded_ = 0;
};

}  // namespace bmp::tracker

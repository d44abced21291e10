#include "tracker/detection_book.hpp"

#include <algorithm>
#include <cstdint>
#include <iterator>

namespace bmp::tracker {

namespace {

template <typename Map>
void eraseOtherStamps(Map& by_key, int64_t seq, int64_t utime) {
  for (auto it = by_key.lower_bound({seq, INT64_MIN}); it != by_key.end() && it->first.first == seq;)
    it = it->first.second == utime ? std::next(it) : by_key.erase(it);
}

// Removes the entries of seq above `seq`; returns how many.
template <typename Map>
std::size_t eraseAbove(Map& by_key, int64_t seq) {
  const auto first = by_key.upper_bound({seq, INT64_MAX});
  const auto n = static_cast<std::size_t>(std::distance(first, by_key.end()));
  by_key.erase(first, by_key.end());
  return n;
}

bool sameAnswer(const FrameBoxes& a, const FrameBoxes& b) {
  const auto same = [](const ObjectBox& x, const ObjectBox& y) {
    return x.box == y.box && x.level == y.level && x.class_id == y.class_id && x.score == y.score;
  };
  return a.usable == b.usable && a.boxes.size() == b.boxes.size() &&
         std::equal(a.boxes.begin(), a.boxes.end(), b.boxes.begin(), same);
}

}  // namespace

void DetectionBook::frameHeard(int64_t seq, int64_t utime) {
  const std::lock_guard<std::mutex> lock(mutex_);
  // Frames are heard in seq order but for a restarted capture (seq from 0 again): the old stream's frames
  // and answers are forgotten, or the new stream's, lowest in seq, would be the first pushed out below.
  if (!heard_.empty() && seq < heard_.rbegin()->first) {
    heard_.clear();
    discarded_ += static_cast<int64_t>(eraseAbove(by_frame_, seq));
    eraseAbove(recent_, seq);
    eraseAbove(taken_, seq);
  }
  heard_[seq] = utime;
  while (heard_.size() > capacity_) heard_.erase(heard_.begin());
  eraseOtherStamps(by_frame_, seq, utime);
  eraseOtherStamps(recent_, seq, utime);
  // Heard now, so nothing was taken for it in this stream: a replay restarted from its first frame stamps
  // its frames as before, and their answers are news.
  taken_.erase(taken_.lower_bound({seq, INT64_MIN}), taken_.upper_bound({seq, INT64_MAX}));
}

std::string DetectionBook::add(int64_t seq, FrameBoxes boxes) {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    const int64_t utime = boxes.utime;
    if (const auto h = heard_.find(seq); h != heard_.end() && h->second != utime)
      return "answer for frame " + std::to_string(seq) + " has stamp " + std::to_string(utime) +
             " us, the frame's is " + std::to_string(h->second);
    const auto first = by_frame_.lower_bound({seq, INT64_MIN});
    std::size_t waiting = 0;
    for (auto it = first; it != by_frame_.end() && it->first.first == seq; ++it) ++waiting;
    if (waiting >= kMaxPerSeq && by_frame_.count({seq, utime}) == 0)
      return "frame " + std::to_string(seq) + " already has " + std::to_string(waiting) +
             " answers waiting with other stamps";
    // The first answer stands: a second one would hide the boxes of the first, or, once the first was
    // taken, be taken again as late boxes. The same answer again is the detector answering a frame lockstep
    // capture sent again.
    if (const auto taken = taken_.find({seq, utime}); taken != taken_.end())
      return sameAnswer(taken->second, boxes)
                 ? ""
                 : "a second, different answer for frame " + std::to_string(seq) + ", which took its first";
    if (const auto waiting_one = by_frame_.find({seq, utime}); waiting_one != by_frame_.end())
      return sameAnswer(waiting_one->second, boxes)
                 ? ""
                 : "a second, different answer for frame " + std::to_string(seq) + "; the first kept";
    // Stand-ins only from frames heard: answers for frames to come (forged) would push the real ones out.
    if (boxes.usable && heard_.count(seq) > 0) {
      recent_[{seq, utime}] = boxes;
      while (recent_.size() > kRecent) recent_.erase(recent_.begin());
    }
    by_frame_[{seq, utime}] = std::move(boxes);
    while (by_frame_.size() > capacity_) {
      by_frame_.erase(by_frame_.begin());
      ++discarded_;
    }
  }
  arrived_.notify_all();
  return "";
}

std::optional<FrameBoxes> DetectionBook::take(int64_t seq, int64_t utime, std::chrono::milliseconds wait) {
  std::unique_lock<std::mutex> lock(mutex_);
  const std::pair<int64_t, int64_t> key{seq, utime};
  arrived_.wait_for(lock, wait, [&] { return by_frame_.count(key) > 0; });
  const auto it = by_frame_.find(key);
  if (it == by_frame_.end()) return std::nullopt;
  FrameBoxes out = std::move(it->second);
  by_frame_.erase(it);
  taken_[key] = out;
  while (taken_.size() > capacity_) taken_.erase(taken_.begin());
  return out;
}

std::vector<FrameBoxes> DetectionBook::newestBefore(int64_t seq, int64_t min_seq, std::size_t n) const {
  const std::lock_guard<std::mutex> lock(mutex_);
  std::vector<FrameBoxes> out;
  for (auto it = recent_.rbegin(); it != recent_.rend() && out.size() < n; ++it) {
    if (it->first.first >= seq) continue;
    if (it->first.first < min_seq) break;  // ordered by seq: the rest are older still
    out.push_back(it->second);
  }
  return out;
}

std::size_t DetectionBook::size() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return by_frame_.size();
}

int64_t DetectionBook::discarded() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return discarded_;
}

}  // namespace bmp::tracker

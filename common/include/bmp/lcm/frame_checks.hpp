#pragma once
// What every consumer of RGBD_FRAME checks before it uses a frame, beyond decoding: a frame can decode
// perfectly and still be unusable (fx = NaN, a depth image of another size, a PNG declared as raw) or
// belong to another stream (stamps going back, another camera). One home for the rules, so the tracker,
// the detector and any tool refuse the same frames with the same words.
#include <cstdint>
#include <deque>
#include <optional>
#include <set>
#include <string>

#include <bmp/rgbd_frame_t.hpp>

#include "bmp/common/camera_model.hpp"
#include "bmp/lcm/camera_pin.hpp"

namespace bmp {

// seq and utime beyond this (2^62: 146 000 years of microseconds) are another publisher's, and keeping
// them out keeps every difference of two of them free of overflow.
inline constexpr int64_t kMaxFrameCounter = int64_t{1} << 62;

// Why the frame cannot be used on its own (seq or stamp negative or beyond kMaxFrameCounter, intrinsics,
// sizes, encodings, depth scale), or "".
std::string checkFrame(const rgbd_frame_t& msg);

// Bounds of a plausible frame stream. A frame beyond them is refused rather than trusted, so one forged
// frame (seq = INT64_MAX, a stamp in the year 3000) cannot make every later real frame look old.
struct FrameStreamLimits {
  int64_t max_seq_gap = 10000;     // frames; a 3 s pause at 30 Hz is 90
  double max_stamp_gap_s = 600.0;  // seconds between consecutive accepted frames
  int resync_frames = 5;           // consecutive, mutually ordered frames that start a new stream
  // A frame this far ahead of the last (seq or stamp) is provisional: when the next frame follows the last
  // instead, the jump was another publisher's, and the stream goes on at once, its count of lost frames
  // mended. Nearer jumps stay final, as frames merely reordered on the network go no further back.
  int64_t provisional_jump_frames = 30;
  double provisional_jump_s = 1.0;
  // Frames accepted with one camera before it is kept for the run. Until then a frame from another camera
  // replaces it: one forged frame before the capture's first must not lock every real frame out.
  int settle_frames = 5;
  // Accepted frames remembered by (seq, stamp), so a damaged copy of one is known for what it is.
  int remembered_frames = 64;
};

// One consumer's view of the frame stream. accept() refuses frames that fail checkFrame, whose seq or
// stamp does not move forward (or jumps beyond the limits), or whose camera differs from the stream's
// first once settled (a camera change mid-run needs a restart: a map built with one camera is wrong for
// another; before it settles, another camera replaces it and the verdict says so). It
// counts frames lost upstream from gaps in seq, so every frame capture published after the first one
// received is either handled, refused with a reason, or counted as lost. A capture that restarts (seq and
// stamps from the beginning) is followed once resync_frames of its frames arrived in order.
class FrameStream {
 public:
  struct Verdict {
    bool ok = true;
    std::string reason;       // why refused (the rule), or why the stream re-synchronised; no seq
    int64_t lost_before = 0;  // frames missing between the last accepted one and this one
    // The last accepted frame again (same seq and stamp): lockstep capture resends a frame whose answer is
    // late, as the frame or the answer may have been lost. Not refused and not used twice: the consumer
    // repeats its answer if it has given it, or lets the pending one go out.
    bool repeat = false;
    // This frame's camera replaced an unsettled one: whatever was built from the earlier frames (a map)
    // belongs to another camera, likely a forged frame's, and is to be dropped.
    bool new_camera = false;
    // The stream's camera has settle_frames accepted frames: what was built from it may be announced.
    bool camera_settled = false;
    // Refused (damaged, another camera, or out of order), yet naming the seq and stamp of a frame accepted
    // shortly before: another publisher's copy, broken or replayed. Not to be answered: an answer under
    // that frame's name would stand for the real frame's, which is coming or came. The reason says so.
    bool copies_accepted = false;
  };
  explicit FrameStream(FrameStreamLimits limits = {}) : limits_(limits), camera_(limits.settle_frames) {}
  Verdict accept(const rgbd_frame_t& msg);

  int64_t accepted() const { return accepted_; }
  int64_t refused() const { return refused_; }
  int64_t lostBefore() const { return lost_before_; }
  int64_t resyncs() const { return resyncs_; }
  int64_t repeats() const { return repeats_; }
  int64_t cameraChanges() const { return camera_changes_; }
  // The stream's camera (pinned by its first accepted frame, or by the one that replaced it), or nullptr.
  const camera_t* camera() const { return camera_.camera(); }

 private:
  struct Position {
    int64_t seq = -1;
    int64_t utime = 0;
  };
  // Why `next` cannot follow `last`, or "".
  std::string orderProblem(const Position& last, const Position& next) const;
  Verdict decide(const rgbd_frame_t& msg);
  Verdict refuse(const rgbd_frame_t& msg, const std::string& why);
  Verdict take(const rgbd_frame_t& msg, std::string note);
  // Makes msg's camera the stream's and msg its first frame.
  Verdict pin(const rgbd_frame_t& msg, std::string note);
  // Frames missing before msg (counted once: a refused frame arrived, so it is refused, not lost).
  int64_t countGap(const rgbd_frame_t& msg);
  // Refuses a frame (damaged: unusable in itself; else out of order), noting whether it names a recently
  // accepted frame: not to be answered then.
  Verdict refuseNaming(const rgbd_frame_t& msg, const std::string& why, bool damaged);

  FrameStreamLimits limits_;
  CameraPin camera_;
  Position last_;                    // the last accepted frame
  std::deque<Position> recent_;      // the last remembered_frames accepted, oldest first
  std::optional<int64_t> seen_seq_;  // the highest seq counted: accepted, or refused between accepted ones
  std::set<int64_t> refused_ahead_;  // seqs refused beyond seen_seq_, not yet passed by an accepted frame
  Position candidate_;               // the newest out-of-order frame, which may be a restarted capture's
  // The last frame accepted jumped far ahead: where the stream was before it, and the frames counted as
  // lost for it.
  struct Jump {
    Position from;
    int64_t counted_lost = 0;
  };
  std::optional<Jump> jump_;
  bool isFarJump(const Position& from, const Position& to) const;
  int candidate_run_ = 0;
  int64_t accepted_ = 0, refused_ = 0, lost_before_ = 0, resyncs_ = 0, repeats_ = 0, camera_changes_ = 0;
};

}  // namespace bmp

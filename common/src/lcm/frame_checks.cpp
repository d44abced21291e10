#include "bmp/lcm/frame_checks.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>

#include "bmp/common/camera_model.hpp"
#include "bmp/common/image_codec.hpp"
#include "bmp/lcm/conversions.hpp"

namespace bmp {

namespace {

// Refused seqs remembered ahead of the stream: the nearest ones; farther ones are more likely forged.
constexpr std::size_t kRefusedAheadKept = 1024;

std::string checkImage(const image_t& img, const camera_t& cam, int8_t pixel_format, const char* what) {
  const std::string name(what);
  if (img.width != cam.width || img.height != cam.height)
    return name + " image is " + std::to_string(img.width) + "x" + std::to_string(img.height) +
           ", the camera " + std::to_string(cam.width) + "x" + std::to_string(cam.height);
  if (img.pixel_format != pixel_format) return name + " image has the wrong pixel format";
  if (img.size <= 0) return name + " image is empty";
  switch (img.encoding) {
    case image_t::ENCODING_RAW: {
      const int64_t channels = pixel_format == image_t::PIXEL_BGR8     ? 3
                               : pixel_format == image_t::PIXEL_MONO16 ? 2
                                                                       : 1;
      if (int64_t{img.size} != int64_t{img.width} * img.height * channels)
        return name + " image is declared raw but holds " + std::to_string(img.size) + " bytes";
      return "";
    }
    case image_t::ENCODING_PNG:
      if (img.size < 8 || img.data[0] != 0x89 || img.data[1] != 'P' || img.data[2] != 'N' ||
          img.data[3] != 'G')
        return name + " image is declared PNG but is not";
      return "";
    case image_t::ENCODING_JPEG:
      if (pixel_format == image_t::PIXEL_MONO16) return name + " image: 16-bit depth cannot be JPEG";
      if (img.size < 4 || img.data[0] != 0xFF || img.data[1] != 0xD8)
        return name + " image is declared JPEG but is not";
      return "";
    default:
      return name + " image has unknown encoding " + std::to_string(img.encoding);
  }
}

// Why an encoded image's structure is broken (truncated, bad CRC, no end marker) or its header's size is
// not the declared one, or "". A whole walk over the bytes: asked only while the camera is unsettled.
std::string structureProblem(const image_t& img, const char* what) {
  if (img.encoding != image_t::ENCODING_PNG && img.encoding != image_t::ENCODING_JPEG) return "";
  try {
    const ImageProbe probe = probeEncodedImage(img.data);
    if (probe.width != img.width || probe.height != img.height)
      return std::string(what) + " image's header says " + std::to_string(probe.width) + "x" +
             std::to_string(probe.height) + ", declared " + std::to_string(img.width) + "x" +
             std::to_string(img.height);
    return "";
  } catch (const ImageError& e) {
    return std::string(what) + " image: " + e.what();
  }
}

}  // namespace

std::string checkFrame(const rgbd_frame_t& msg) {
  if (msg.seq < 0 || msg.seq > kMaxFrameCounter) return "seq " + std::to_string(msg.seq) + " is out of range";
  if (msg.utime < 0 || msg.utime > kMaxFrameCounter)
    return "stamp " + std::to_string(msg.utime) + " us is out of range";
  if (std::string why = intrinsicsProblem(fromMsg(msg.camera, msg.depth_scale)); !why.empty()) return why;
  if (std::string why = checkImage(msg.color, msg.camera, image_t::PIXEL_BGR8, "colour"); !why.empty())
    return why;
  return checkImage(msg.depth, msg.camera, image_t::PIXEL_MONO16, "depth");
}

std::string FrameStream::orderProblem(const Position& last, const Position& next) const {
  if (next.seq <= last.seq)
    return "seq " + std::to_string(next.seq) + " does not follow " + std::to_string(last.seq);
  if (next.seq - last.seq > limits_.max_seq_gap)
    return "seq jumps from " + std::to_string(last.seq) + " to " + std::to_string(next.seq);
  if (next.utime <= last.utime) return "stamp is not after the previous frame's";
  if (static_cast<double>(next.utime - last.utime) > limits_.max_stamp_gap_s * 1e6)
    return "stamp jumps " + std::to_string((next.utime - last.utime) / 1000000) + " s ahead";
  return "";
}

FrameStream::Verdict FrameStream::refuse(const rgbd_frame_t& msg, const std::string& why) {
  ++refused_;
  (void)msg;
  return {false, why, 0};
}

FrameStream::Verdict FrameStream::refuseNaming(const rgbd_frame_t& msg, const std::string& why,
                                               bool damaged) {
  const bool copy = std::any_of(recent_.begin(), recent_.end(),
                                [&](const Position& p) { return p.seq == msg.seq && p.utime == msg.utime; });
  const char* note = damaged ? " (a damaged copy of a frame taken; not answered)"
                             : " (a copy of a frame taken before; not answered)";
  Verdict v = refuse(msg, copy ? why + note : why);
  v.copies_accepted = copy;
  return v;
}

FrameStream::Verdict FrameStream::take(const rgbd_frame_t& msg, std::string note) {
  last_ = {msg.seq, msg.utime};
  recent_.push_back(last_);
  while (static_cast<int>(recent_.size()) > limits_.remembered_frames) recent_.pop_front();
  candidate_run_ = 0;
  ++accepted_;
  camera_.used();
  Verdict v{true, std::move(note), 0};
  v.camera_settled = camera_.settled();
  return v;
}

FrameStream::Verdict FrameStream::pin(const rgbd_frame_t& msg, std::string note) {
  camera_.pin(msg.camera, msg.depth_scale);
  seen_seq_ = msg.seq;  // the new camera's stream is counted from here
  return take(msg, std::move(note));
}

int64_t FrameStream::countGap(const rgbd_frame_t& msg) {
  if (msg.seq < 0 || msg.seq > kMaxFrameCounter) return 0;  // refused by checkFrame; not a position
  if (!seen_seq_) {
    seen_seq_ = msg.seq;  // frames published before we listened are not ours to count
    return 0;
  }
  if (msg.seq <= *seen_seq_ || msg.seq - *seen_seq_ > limits_.max_seq_gap) return 0;
  // Frames refused in between arrived: refused, not lost.
  const auto arrived =
      std::distance(refused_ahead_.upper_bound(*seen_seq_), refused_ahead_.lower_bound(msg.seq));
  const int64_t gap = msg.seq - *seen_seq_ - 1 - static_cast<int64_t>(arrived);
  seen_seq_ = msg.seq;
  lost_before_ += gap;
  return gap;
}

bool FrameStream::isFarJump(const Position& from, const Position& to) const {
  return to.seq - from.seq > limits_.provisional_jump_frames ||
         static_cast<double>(to.utime - from.utime) > limits_.provisional_jump_s * 1e6;
}

FrameStream::Verdict FrameStream::accept(const rgbd_frame_t& msg) {
  if (accepted_ > 0 && msg.seq == last_.seq && msg.utime == last_.utime && checkFrame(msg).empty() &&
      camera_.fit(msg.camera, msg.depth_scale) == CameraPin::Fit::kSame) {
    ++repeats_;
    Verdict v{false, "a repeat of frame " + std::to_string(msg.seq) + " (resent by lockstep capture)", 0};
    v.repeat = true;
    return v;
  }
  const Position before = last_;
  const bool first = accepted_ == 0;
  const std::optional<int64_t> seen_before = seen_seq_;
  const int64_t lost_so_far = lost_before_;
  const int64_t gap = countGap(msg);
  Verdict v = decide(msg);
  if (!v.ok) {
    // A refused frame moves no count: its seq may be another stream's (one forged seq 9010 made 9000 frames
    // lost, and hid the real stream's losses after it). Its own seq, ahead of ours, is remembered: it
    // arrived, so it is not lost when the stream passes it.
    seen_seq_ = seen_before;
    lost_before_ = lost_so_far;
    v.lost_before = 0;
    if (seen_seq_ && msg.seq > *seen_seq_ && msg.seq - *seen_seq_ <= limits_.max_seq_gap) {
      refused_ahead_.insert(msg.seq);
      if (refused_ahead_.size() > kRefusedAheadKept) refused_ahead_.erase(std::prev(refused_ahead_.end()));
    }
    return v;
  }
  if (seen_seq_) refused_ahead_.erase(refused_ahead_.begin(), refused_ahead_.upper_bound(*seen_seq_));
  v.lost_before += gap;
  if (v.new_camera) {  // a gap from the replaced camera's frames is not a loss of this stream's
    lost_before_ -= gap;
    v.lost_before -= gap;
  }
  if (v.ok && !v.new_camera && !first && isFarJump(before, last_))
    jump_ = Jump{before, gap};
  else if (v.ok)
    jump_.reset();
  return v;
}

FrameStream::Verdict FrameStream::decide(const rgbd_frame_t& msg) {
  if (std::string why = checkFrame(msg); !why.empty()) return refuseNaming(msg, why, true);
  // Until the camera settles, each accepted frame counts towards keeping its camera for the run: a few
  // frames of junk must not count (they would lock the real camera out), so their images are walked whole.
  if (!camera_.settled()) {
    std::string why = structureProblem(msg.color, "colour");
    if (why.empty()) why = structureProblem(msg.depth, "depth");
    if (!why.empty()) return refuseNaming(msg, why, true);
  }
  switch (camera_.fit(msg.camera, msg.depth_scale)) {
    case CameraPin::Fit::kFirst:
      return pin(msg, "");
    case CameraPin::Fit::kRefused:
      return refuseNaming(msg, camera_.refusal(msg.camera, msg.depth_scale), true);
    case CameraPin::Fit::kReplaces: {
      ++camera_changes_;
      Verdict v = pin(msg, camera_.replacement(msg.camera, msg.depth_scale));
      v.new_camera = true;
      return v;
    }
    case CameraPin::Fit::kSame:
      break;
  }
  const Position next{msg.seq, msg.utime};
  const std::string why = orderProblem(last_, next);
  if (why.empty()) return take(msg, "");
  if (jump_ && orderProblem(jump_->from, next).empty()) {
    // The stream goes on from before the jump: the frame that jumped was another publisher's. Its gap
    // was no loss; the frames between where the stream was and this one are.
    const Jump jump = *jump_;
    const int64_t lost = next.seq - jump.from.seq - 1;
    lost_before_ += lost - jump.counted_lost;
    seen_seq_ = next.seq;
    Verdict v = take(msg, "frame seq " + std::to_string(last_.seq) +
                              " jumped ahead of the stream, which goes on from seq " +
                              std::to_string(jump.from.seq) + ": taken as another publisher's");
    v.lost_before = lost - jump.counted_lost;
    return v;
  }
  // Out of order: a forged frame, or the first frames of a restarted capture. Only a run of frames in
  // order among themselves is followed.
  candidate_run_ = (candidate_run_ > 0 && orderProblem(candidate_, next).empty()) ? candidate_run_ + 1 : 1;
  candidate_ = next;
  if (candidate_run_ < limits_.resync_frames) return refuseNaming(msg, why, false);
  ++resyncs_;
  seen_seq_ = msg.seq;
  return take(msg, "stream re-synchronised after " + std::to_string(limits_.resync_frames) +
                       " frames out of order (" + why + ")");
}

}  // namespace bmp

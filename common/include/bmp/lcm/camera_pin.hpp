#pragma once
// The one camera a consumer works with. A map built with one camera is wrong for another, so the camera of
// the first messages is kept for the run; but one forged message sent before the real first must not lock
// the real camera out. So the camera settles only after settle_count messages were used with it, and until
// then another camera replaces it (the consumer drops what it built and starts again).
#include <cstdint>
#include <optional>
#include <string>

#include <bmp/camera_t.hpp>

namespace bmp {

class CameraPin {
 public:
  enum class Fit {
    kFirst,     // no camera yet: this one becomes it
    kSame,      // the camera
    kReplaces,  // another camera, and the current one has not settled: this one takes its place
    kRefused,   // another camera after the current one settled
  };
  explicit CameraPin(int settle_count) : settle_count_(settle_count) {}

  // How a message's camera fits; changes nothing.
  Fit fit(const camera_t& camera, double depth_scale) const;
  // Makes this the camera (after kFirst or kReplaces), with no message used yet.
  void pin(const camera_t& camera, double depth_scale);
  // One more message used with the camera.
  void used() { ++uses_; }
  bool settled() const { return pinned_ && uses_ >= settle_count_; }
  const camera_t* camera() const { return pinned_ ? &pinned_->camera : nullptr; }
  // Whether this is the pinned camera (false when none is pinned).
  bool holds(const camera_t& camera, double depth_scale) const {
    return fit(camera, depth_scale) == Fit::kSame;
  }
  int64_t uses() const { return uses_; }
  // "640x480 fx ... depth scale 5000" for this camera, or for another one.
  std::string describe() const;
  static std::string describe(const camera_t& camera, double depth_scale);
  // Why a camera that does not fit is refused, or why it replaces the current one.
  std::string refusal(const camera_t& camera, double depth_scale) const;
  std::string replacement(const camera_t& camera, double depth_scale) const;

 private:
  struct Pinned {
    camera_t camera;
    double depth_scale = 0;
  };
  int settle_count_;
  std::optional<Pinned> pinned_;
  int64_t uses_ = 0;
};

}  // namespace bmp

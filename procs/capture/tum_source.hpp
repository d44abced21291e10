#pragma once
// Frames from a TUM-format folder, as the bytes of their files. Every file is checked before it is offered:
// a missing, corrupt or wrongly-sized image is skipped with a warning and counted, never invented.
#include <functional>
#include <string>

#include "capture/frame_source.hpp"
#include "capture/tum_sequence.hpp"

namespace bmp::capture {

enum class VerifyMode {
  kHeader,  // structure only (PNG chunk CRCs, JPEG markers, sizes): cheap, keeps fast mode fast
  kDecode,  // full decode of both images
};

struct FrameSelection {
  int64_t start = 0;  // first associated frame to play
  int64_t end = -1;   // one past the last; -1 plays to the end
  int64_t every = 1;  // play every n-th frame
};

// How many of frames [0, total) the selection plays; free of overflow for any start >= 0 and every >= 1
// (--every 9223372036854775807 read past the end of the frame list).
int64_t selectedCount(const FrameSelection& selection, int64_t total);
// One past the last of frames [0, total) the selection may play.
int64_t selectedEnd(const FrameSelection& selection, int64_t total);

struct TumSourceOptions {
  FrameSelection selection;
  VerifyMode verify = VerifyMode::kHeader;
  std::function<void(const std::string&)> warn;  // receives one line per skipped frame
};

class TumSource : public FrameSource {
 public:
  TumSource(SequenceIndex index, const CameraIntrinsics& camera, TumSourceOptions options);

  std::optional<CapturedFrame> next() override;
  const CameraIntrinsics& camera() const override { return camera_; }
  std::string name() const override { return index_.name; }
  int64_t size() const override;
  const SkipReport& skips() const override { return skips_; }
  const SequenceIndex& index() const { return index_; }

 private:
  // Reads and checks one image; returns false (and counts why) when the frame must be skipped.
  bool load(const std::string& path, bool is_depth, EncodedImage& out);
  void skip(int64_t& counter, const std::string& reason);
  // Whether a listed file's stamp falls among the frames this source plays (its missing files are counted).
  bool inPlayedRange(double stamp) const;

  SequenceIndex index_;
  CameraIntrinsics camera_;
  TumSourceOptions options_;
  int64_t cursor_;
  SkipReport skips_;
};

VerifyMode parseVerifyMode(const std::string& text);  // "header" | "decode"; throws std::invalid_argument
const char* toString(VerifyMode mode);

}  // namespace bmp::capture

#include "capture/tum_source.hpp"

#include <algorithm>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <system_error>

namespace bmp::capture {

namespace {

// Why a path that is no regular file cannot be read, for a skip line: a folder (or the like) there, or
// nothing. listed: said of a file the lists name, before any frame.
std::string absence(const std::string& path, bool listed) {
  std::error_code unreadable;  // a symlink loop: nothing there to read
  if (std::filesystem::exists(path, unreadable))
    return listed ? ": listed, but not a file (a folder?)" : ": not a file (a folder?)";
  return listed ? ": listed but does not exist" : ": file does not exist";
}

}  // namespace

TumSource::TumSource(SequenceIndex index, const CameraIntrinsics& camera, TumSourceOptions options)
    : index_(std::move(index)), camera_(camera), options_(std::move(options)) {
  if (options_.selection.every < 1) throw std::invalid_argument("frame selection: every must be >= 1");
  if (options_.selection.start < 0) throw std::invalid_argument("frame selection: start must be >= 0");
  // Nothing would play, and "0 frames" would end the run without a reason.
  if (options_.selection.start >= static_cast<int64_t>(index_.frames.size()))
    throw std::invalid_argument("--start " + std::to_string(options_.selection.start) +
                                " is past the end of " + index_.name + " (" +
                                std::to_string(index_.frames.size()) + " associated frames)");
  cursor_ = options_.selection.start;
  for (const auto& file : index_.missing_files)
    if (inPlayedRange(file.stamp)) skip(skips_.missing_files, file.path + absence(file.path, true));
}

bool TumSource::inPlayedRange(double stamp) const {
  // From the first played frame up to the first frame after the range: consecutive ranges share out the
  // missing files, and a file before the sequence's first frame belongs to a range that starts there.
  const auto total = static_cast<int64_t>(index_.frames.size());
  const auto first_stamp = [&](int64_t i) {
    const FramePair& f = index_.frames[static_cast<std::size_t>(i)];
    return std::min(f.rgb_stamp, f.depth_stamp);
  };
  const int64_t start = options_.selection.start;
  const int64_t end = selectedEnd(options_.selection, total);
  if (start >= end) return false;
  return (start == 0 || stamp >= first_stamp(start)) && (end == total || stamp < first_stamp(end));
}

int64_t selectedEnd(const FrameSelection& selection, int64_t total) {
  return selection.end < 0 ? total : std::min(total, selection.end);
}

int64_t selectedCount(const FrameSelection& selection, int64_t total) {
  const int64_t end = selectedEnd(selection, total);
  return end <= selection.start ? 0 : (end - selection.start - 1) / selection.every + 1;
}

int64_t TumSource::size() const {
  return selectedCount(options_.selection, static_cast<int64_t>(index_.frames.size()));
}

void TumSource::skip(int64_t& counter, const std::string& reason) {
  ++counter;
  skips_.last_reason = reason;
  if (options_.warn) options_.warn("skipped " + reason);
}

bool TumSource::load(const std::string& path, bool is_depth, EncodedImage& out) {
  std::error_code unreadable;  // a symlink loop: missing, not an exception that ends the run
  if (!std::filesystem::is_regular_file(path, unreadable)) {
    skip(skips_.missing_files, path + absence(path, false));
    return false;
  }
  std::vector<uint8_t> bytes;
  ImageProbe probe;
  try {
    bytes = readFileBytes(path);
    probe = probeEncodedImage(bytes);
  } catch (const ImageError& e) {
    skip(skips_.corrupt_files, path + ": " + e.what());
    return false;
  }
  const bool format_ok =
      is_depth
          ? (probe.encoding == ImageEncoding::kPng && probe.bit_depth == 16 && probe.channels == 1)
          : (probe.bit_depth == 8 && (probe.channels == 3 || probe.channels == 4 || probe.channels == 1));
  if (!format_ok) {
    skip(skips_.corrupt_files,
         path + ": " + (is_depth ? "depth must be a 16-bit single-channel PNG" : "colour must be 8-bit") +
             ", found " + std::to_string(probe.bit_depth) + "-bit, " + std::to_string(probe.channels) +
             " channel(s)");
    return false;
  }
  if (probe.width != camera_.width || probe.height != camera_.height) {
    skip(skips_.wrong_size, path + ": image is " + std::to_string(probe.width) + "x" +
                                std::to_string(probe.height) + ", the camera is " +
                                std::to_string(camera_.width) + "x" + std::to_string(camera_.height));
    return false;
  }
  out.width = probe.width;
  out.height = probe.height;
  out.encoding = probe.encoding;
  out.pixel_format = is_depth ? PixelFormat::kMono16 : PixelFormat::kBgr8;
  out.data = std::move(bytes);
  if (options_.verify == VerifyMode::kDecode) {
    try {
      decodeImage(out);
    } catch (const ImageError& e) {
      skip(skips_.corrupt_files, path + ": " + e.what());
      return false;
    }
  }
  return true;
}

std::optional<CapturedFrame> TumSource::next() {
  const auto total = static_cast<int64_t>(index_.frames.size());
  const int64_t end = selectedEnd(options_.selection, total);
  while (cursor_ < end) {
    const int64_t i = cursor_;
    cursor_ = options_.selection.every >= end - cursor_ ? end : cursor_ + options_.selection.every;
    const FramePair& pair = index_.frames[static_cast<std::size_t>(i)];
    CapturedFrame frame;
    frame.index = i;
    frame.stamp = pair.rgb_stamp;
    frame.depth_stamp = pair.depth_stamp;
    if (!load(pair.rgb_path, false, frame.color) || !load(pair.depth_path, true, frame.depth)) continue;
    return frame;
  }
  return std::nullopt;
}

VerifyMode parseVerifyMode(const std::string& text) {
  if (text == "header") return VerifyMode::kHeader;
  if (text == "decode") return VerifyMode::kDecode;
  throw std::invalid_argument("verify mode must be 'header' or 'decode', got '" + text + "'");
}

const char* toString(VerifyMode mode) {
  return mode == VerifyMode::kDecode ? "decode" : "header";
}

}  // namespace bmp::capture

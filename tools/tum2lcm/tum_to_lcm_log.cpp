#include "tum_to_lcm_log.hpp"

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <vector>

#include <lcm/lcm-cpp.hpp>

#include "bmp/common/arg_range.hpp"
#include "bmp/common/camera_config.hpp"
#include "bmp/common/config_dir.hpp"
#include "bmp/common/log.hpp"
#include "capture/camera_selection.hpp"
#include "capture/lcm/frame_message.hpp"
#include "capture/open_source.hpp"
#include "capture/tum_source.hpp"

namespace bmp::capture {

namespace {

constexpr long long kMaxFrameNumber = 100000000;

void writeEvent(lcm::LogFile& log_file, const std::string& path, const std::string& channel, int64_t seq,
                const rgbd_frame_t& msg, std::vector<uint8_t>& buffer) {
  buffer.resize(static_cast<std::size_t>(msg.getEncodedSize()));
  msg.encode(buffer.data(), 0, static_cast<int>(buffer.size()));
  lcm::LogEvent event;
  event.eventnum = seq;
  event.timestamp = msg.utime;  // lcm-logplayer replays at the recorded rate from these
  event.channel = channel;
  event.datalen = static_cast<int32_t>(buffer.size());
  event.data = buffer.data();
  if (log_file.writeEvent(&event) != 0) throw std::runtime_error(path + ": write failed");
}

}  // namespace

int convertTumToLcmLog(const ArgParser& args) {
  const std::string dir = args.value("dataset");
  const std::string out_path = args.value("out");
  if (dir.empty() || out_path.empty()) throw ArgError("tum2lcm: --dataset and --out are required");
  std::error_code ec;
  if (!args.flag("force") && std::filesystem::exists(std::filesystem::symlink_status(out_path, ec)))
    throw ArgError("tum2lcm: --out '" + out_path + "' exists; give --force to replace it");
  // Found now, not after the whole conversion failed to rename onto it.
  if (std::filesystem::is_directory(std::filesystem::symlink_status(out_path, ec)))
    throw ArgError("tum2lcm: --out '" + out_path + "' is a folder; give a file name");
  const std::string channel = args.value("channel");
  if (channel.empty()) throw ArgError("tum2lcm: --channel must name a channel");
  TumSourceOptions options;
  options.selection = {integerIn(args, "start", 0, kMaxFrameNumber),
                       integerIn(args, "end", -1, kMaxFrameNumber),
                       integerIn(args, "every", 1, kMaxFrameNumber)};
  if (options.selection.end >= 0 && options.selection.end <= options.selection.start)
    throw ArgError("tum2lcm: --end must be past --start (it is one past the last frame written)");
  try {
    options.verify = parseVerifyMode(args.value("verify"));
  } catch (const std::invalid_argument& e) {
    throw ArgError(std::string("tum2lcm: --verify: ") + e.what());
  }
  options.warn = [](const std::string& m) { log::warn(m); };
  const double max_diff = positiveNumber(args, "max-diff");
  // The folder first: a missing or empty one is said as such, not as an unknown camera.
  SequenceIndex index = indexSequence(dir, max_diff);
  const SequenceCamera selected = selectCamera(dir, args.value("camera"), configDir() + "/cameras");
  const CameraIntrinsics& camera = selected.intrinsics;
  logSequenceFindings(index, selected);  // as bmp-capture: the log is played later, without the folder
  TumSource source = [&] {
    try {
      return TumSource(std::move(index), camera, options);
    } catch (const std::invalid_argument& e) {  // the frame selection (--start past the end): a usage error
      throw ArgError(std::string("tum2lcm: ") + e.what());
    }
  }();

  // Written beside --out and renamed when whole: a run that fails leaves a log already there as it was.
  const std::string partial = out_path + ".partial";
  // One left by a killed run, or a link planted there, is removed (the link itself, not what it names):
  // opened as it was, a link to another file had that file overwritten with the log.
  std::filesystem::remove(partial, ec);
  std::vector<uint8_t> buffer;
  int64_t seq = 0;
  try {
    lcm::LogFile log_file(partial, "w");
    if (!log_file.good()) throw std::runtime_error(partial + ": cannot open for writing");
    while (auto frame = source.next()) {
      const rgbd_frame_t msg = toFrameMessage(std::move(*frame), seq, camera, source.name());
      writeEvent(log_file, partial, channel, seq, msg, buffer);
      ++seq;
      if (seq % 100 == 0) log::info("written ", seq, "/", source.size(), " frames");
    }
  } catch (...) {
    std::remove(partial.c_str());
    throw;
  }
  if (seq == 0) {
    std::remove(partial.c_str());
    throw std::runtime_error(dir + ": no frame could be read (each skip is named above); " + out_path +
                             " not written");
  }
  if (std::rename(partial.c_str(), out_path.c_str()) != 0)
    throw std::runtime_error(out_path + ": cannot be written: " + std::strerror(errno));
  log::info("wrote ", seq, " frames to ", out_path, " (skipped ", source.skips().total(), ")");
  return 0;
}

}  // namespace bmp::capture

#include "tum_to_lcm_log.hpp"

#include <cstdint>
#include <stdexcept>
#include <vector>

#include <lcm/lcm-cpp.hpp>

#include "bmp/common/camera_config.hpp"
#include "bmp/common/config_dir.hpp"
#include "bmp/common/log.hpp"
#include "capture/camera_selection.hpp"
#include "capture/lcm/frame_message.hpp"
#include "capture/tum_source.hpp"

namespace bmp::capture {

namespace {

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
  const CameraIntrinsics camera =
      selectCamera(dir, args.value("camera"), configDir() + "/cameras").intrinsics;

  TumSourceOptions options;
  options.selection = {args.integer("start"), args.integer("end"), args.integer("every")};
  options.verify = parseVerifyMode(args.value("verify"));
  options.warn = [](const std::string& m) { log::warn(m); };
  TumSource source(indexSequence(dir, args.number("max-diff")), camera, options);

  lcm::LogFile log_file(out_path, "w");
  if (!log_file.good()) throw std::runtime_error(out_path + ": cannot open for writing");
  const std::string channel = args.value("channel");
  std::vector<uint8_t> buffer;
  int64_t seq = 0;
  while (auto frame = source.next()) {
    const rgbd_frame_t msg = toFrameMessage(std::move(*frame), seq, camera, source.name());
    writeEvent(log_file, out_path, channel, seq, msg, buffer);
    ++seq;
    if (seq % 100 == 0) log::info("written ", seq, "/", source.size(), " frames");
  }
  log::info("wrote ", seq, " frames to ", out_path, " (skipped ", source.skips().total(), ")");
  return seq > 0 ? 0 : 1;
}

}  // namespace bmp::capture

// tum2lcm: writes a TUM-format folder as an LCM log of RGBD_FRAME messages, for lcm-logplayer.
#include <cstdio>
#include <iostream>
#include <vector>

#include <lcm/lcm-cpp.hpp>

#include "bmp/common/arg_parser.hpp"
#include "bmp/common/camera_config.hpp"
#include "bmp/common/log.hpp"
#include "bmp/common/tool_main.hpp"
#include "bmp/lcm/process.hpp"
#include "capture/camera_selection.hpp"
#include "capture/lcm/frame_message.hpp"
#include "capture/tum_source.hpp"

namespace {

using namespace bmp;
using namespace bmp::capture;

int convert(const ArgParser& args) {
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
    rgbd_frame_t msg = toFrameMessage(std::move(*frame), seq, camera, source.name());
    buffer.resize(static_cast<std::size_t>(msg.getEncodedSize()));
    msg.encode(buffer.data(), 0, static_cast<int>(buffer.size()));
    lcm::LogEvent event;
    event.eventnum = seq;
    event.timestamp = msg.utime;  // lcm-logplayer replays at the recorded rate from these
    event.channel = channel;
    event.datalen = static_cast<int32_t>(buffer.size());
    event.data = buffer.data();
    if (log_file.writeEvent(&event) != 0) throw std::runtime_error(out_path + ": write failed");
    ++seq;
    if (seq % 100 == 0) log::info("written ", seq, "/", source.size(), " frames");
  }
  log::info("wrote ", seq, " frames to ", out_path, " (skipped ", source.skips().total(), ")");
  return seq > 0 ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  ArgParser args("tum2lcm",
                 "Writes a TUM-format RGB-D folder as an LCM log of RGBD_FRAME messages (the files' "
                 "bytes, not re-encoded), stamped with the recorded times, for lcm-logplayer.");
  args.addOption("dataset", "DIR", "TUM-format folder");
  args.addOption("out", "FILE", "LCM log to write");
  args.addOption("camera", "FILE", "camera YAML; default: DIR/camera.yaml, else chosen by the folder name");
  args.addOption("channel", "NAME", "channel of the frames", channels::kFrames);
  args.addOption("start", "N", "first associated frame", "0");
  args.addOption("end", "N", "one past the last frame; -1 = all", "-1");
  args.addOption("every", "K", "every K-th frame", "1");
  args.addOption("verify", "HOW", "header | decode", "header");
  args.addOption("max-diff", "S", "colour/depth association window, seconds", "0.02");
  args.addEpilog(
      "Example:\n  tum2lcm --dataset ../shared/data/rgbd_bonn_crowd --out bonn.lcmlog\n"
      "  lcm-logplayer bonn.lcmlog      # replays RGBD_FRAME into running processes\n");
  return runTool(args, argc, argv, convert);
}

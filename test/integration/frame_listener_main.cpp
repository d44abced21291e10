// bmp-test-listener: a consumer process for integration tests. Receives RGBD_FRAME, checks that both images
// decode, optionally answers each frame on SLAM_POSE (as the tracker does, for lockstep) and/or DETECTIONS
// (as the detector does), at once or after a delay, and writes one report line per frame: "seq utime
// depth_utime color_bytes depth_bytes decoded(0/1)".
#include <chrono>
#include <fstream>
#include <set>
#include <thread>

#include <bmp/detections_t.hpp>
#include <bmp/rgbd_frame_t.hpp>
#include <bmp/slam_pose_t.hpp>

#include "bmp/common/image_codec.hpp"
#include "bmp/common/log.hpp"
#include "bmp/common/timing.hpp"
#include "bmp/lcm/conversions.hpp"
#include "bmp/lcm/process.hpp"

namespace {

using namespace bmp;

void addOptions(ArgParser& args) {
  args.addOption("report", "FILE", "where the per-frame report goes");
  args.addFlag("ack", "answer every frame with a slam_pose_t on SLAM_POSE carrying its seq");
  args.addFlag("ack-detections",
               "answer every frame with a detections_t on DETECTIONS, as the detector does");
  args.addOption("ack-delay-ms", "MS", "wait this long before answering (a slow consumer)", "0");
  args.addFlag("decode", "decode both images of every frame");
  args.addOption("expect", "N", "exit once N frames arrived (0 = run until SIGINT)", "0");
  args.addOption("ignore-once", "SEQ",
                 "act as if frame SEQ's first arrival was lost in the kernel (no report, no answer)", "-1");
}

int run(ProcessContext& ctx) {
  finishConfig(ctx);
  std::ofstream report(ctx.args.value("report"));
  if (!report) throw std::runtime_error(ctx.args.value("report") + ": cannot write report");
  const bool ack = ctx.args.flag("ack");
  const bool ack_detections = ctx.args.flag("ack-detections");
  const auto ack_delay = std::chrono::milliseconds(ctx.args.integer("ack-delay-ms"));
  const bool decode = ctx.args.flag("decode");
  const long long expect = ctx.args.integer("expect");
  long long received = 0;
  long long ignore_once = ctx.args.integer("ignore-once");
  // bmp-capture resends a frame whose answer is late (a loaded machine): answered again, reported once, as
  // the real consumers do, so a report lists each frame once.
  std::set<std::pair<long long, long long>> reported;
  long long resent = 0;
  ctx.lcm.subscribe<rgbd_frame_t>("RGBD_FRAME", [&](const rgbd_frame_t& msg, const ReceivedInfo&) {
    if (msg.seq == ignore_once) {
      ignore_once = -1;
      return;
    }
    const bool again = !reported.insert({msg.seq, msg.utime}).second;
    resent += again;
    bool decoded = true;
    if (decode && !again) {  // a resend's images were checked on its first arrival
      try {
        decodeImage(fromMsg(msg.color));
        decodeImage(fromMsg(msg.depth));
      } catch (const ImageError& e) {
        log::warn("frame ", msg.seq, ": ", e.what());
        decoded = false;
      }
    }
    if (!again) {
      report << msg.seq << " " << msg.utime << " " << msg.depth_utime << " " << msg.color.size << " "
             << msg.depth.size << " " << (decoded ? 1 : 0) << "\n";
      ++received;
      ctx.status.received();
    }
    if ((ack || ack_detections) && ack_delay.count() > 0) std::this_thread::sleep_for(ack_delay);
    if (ack_detections) {
      detections_t answer{};
      answer.utime = msg.utime;
      answer.seq = msg.seq;
      answer.model = "test";
      ctx.lcm.publish("DETECTIONS", answer);
    }
    if (ack) {
      slam_pose_t pose{};
      pose.utime = msg.utime;
      pose.seq = msg.seq;
      ctx.lcm.publish("SLAM_POSE", pose);
    }
  });
  // The first heartbeat goes out here, after the subscription: bmp-capture --wait-for takes a heartbeat to
  // mean this listener hears frames.
  while (!ctx.stop.requested() && (expect == 0 || received < expect)) {
    ctx.lcm.handle(50);
    ctx.status.tick();
  }
  // Datagrams still queued in the socket when stopped are read too: a test stops the listener right after the
  // publisher ends, and on a loaded machine the last ones may not have been handled yet.
  for (long long before = -1; expect == 0 && before != received;) {
    before = received;
    const auto quiet_until = std::chrono::steady_clock::now() + std::chrono::milliseconds(300);
    while (std::chrono::steady_clock::now() < quiet_until && before == received) ctx.lcm.handle(50);
  }
  report.flush();
  log::info("received ", received, " frames (", resent, " resent)");
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return bmp::runProcess(
      argc, argv, {"bmp-test-listener", "Integration-test consumer of RGBD_FRAME.", "", addOptions, run});
}

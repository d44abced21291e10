#include "capture/capture_settings.hpp"

#include <filesystem>
#include <stdexcept>
#include <string>

namespace bmp::capture {

namespace {

// A broken rule names where the value came from: the option when the command line gave it, else the file
// and key. An empty key marks an option with no configuration key, an empty option a key with no option.
class Checker {
 public:
  Checker(const Config& section, const ArgParser& args) : section_(section), args_(args) {}
  void operator()(bool ok, const std::string& key, const std::string& option, const std::string& rule) const {
    if (ok) return;
    if (!option.empty() && (key.empty() || args_.given(option)))
      throw ArgError("--" + option + " '" + args_.value(option) + "': " + rule);
    section_.check(ok, key, rule);
  }

 private:
  const Config& section_;
  const ArgParser& args_;
};

// The configured value, always read (so finish() accepts the key), unless the command line gives one; the
// start-up log then shows the option's value, the one in use.
std::string overridden(const Config& section, const ArgParser& args, const std::string& key,
                       const std::string& option, const std::string& fallback) {
  const std::string configured = section.get<std::string>(key, fallback);
  if (!args.given(option)) return configured;
  section.overridden(key, args.value(option), "--" + option);
  return args.value(option);
}
double overridden(const Config& section, const ArgParser& args, const std::string& key,
                  const std::string& option, double fallback) {
  const double configured = section.get<double>(key, fallback);
  if (!args.given(option)) return configured;
  section.overridden(key, args.value(option), "--" + option);
  return args.number(option);
}

template <typename Mode>
bool parses(Mode (*parse)(const std::string&), const std::string& text, Mode& out) {
  try {
    out = parse(text);
    return true;
  } catch (const std::invalid_argument&) {
    return false;
  }
}

void readPlayerOptions(const Config& section, const ArgParser& args, const Checker& check, PlayerOptions& p) {
  p.channel = section.get<std::string>("channel", p.channel);
  check(!p.channel.empty(), "channel", "", "must not be empty");
  p.ack_channels = section.get<std::vector<std::string>>("ack_channels", p.ack_channels);
  if (args.given("ack-channels")) {
    p.ack_channels = args.list("ack-channels");
    std::string shown;
    for (const auto& c : p.ack_channels) shown += (shown.empty() ? "" : ", ") + c;
    section.overridden("ack_channels", "[" + shown + "]", "--ack-channels");
  }
  const std::string mode = overridden(section, args, "mode", "mode", toString(p.mode));
  check(parses(parseRateMode, mode, p.mode), "mode", "mode",
        "must be realtime, fast or lockstep, got '" + mode + "'");
  // Without an answer to wait for, lockstep would silently play as fast as it can and consumers would drop.
  check(p.mode != RateMode::kLockstep || !p.ack_channels.empty(), "ack_channels", "ack-channels",
        "is empty, but mode lockstep needs at least one answer channel (capture.ack_channels or "
        "--ack-channels)");
  p.speed = overridden(section, args, "speed", "speed", p.speed);
  check(p.speed >= Pacer::kMinSpeed && p.speed <= Pacer::kMaxSpeed, "speed", "speed",
        "must be 0.001 to 1000 (a thousandth of the recorded rate to a thousand times it)");
  p.lockstep_timeout_s = section.get<double>("lockstep_timeout_s", p.lockstep_timeout_s);
  check(p.lockstep_timeout_s > 0, "lockstep_timeout_s", "", "must be positive");
  p.lockstep_resend_factor = section.get<double>("lockstep_resend_factor", p.lockstep_resend_factor);
  check(p.lockstep_resend_factor >= 1, "lockstep_resend_factor", "", "must be at least 1");
  p.lockstep_resend_min_s = section.get<double>("lockstep_resend_min_s", p.lockstep_resend_min_s);
  check(p.lockstep_resend_min_s > 0, "lockstep_resend_min_s", "", "must be positive");
  p.progress_every_s = section.get<double>("progress_every_s", p.progress_every_s);
  check(p.progress_every_s > 0, "progress_every_s", "", "must be positive");
  p.masks_out = args.value("masks-out");
}

void readSelection(const ArgParser& args, const Checker& check, FrameSelection& s) {
  s = {args.integer("start"), args.integer("end"), args.integer("every")};
  check(s.start >= 0, "", "start", "must not be negative");
  check(s.end >= -1, "", "end", "must be -1 (all) or a frame number");
  check(s.every >= 1, "", "every", "must be at least 1");
  // An empty range plays nothing and ended as "published 0 frames", exit 1, without saying why.
  check(s.end < 0 || s.end > s.start, "", "end",
        "must be past --start " + std::to_string(s.start) + " (--end is one past the last frame played)");
}

}  // namespace

void addCaptureOptions(ArgParser& args) {
  args.addOption("dataset", "DIR",
                 "TUM-format folder (rgb.txt, depth.txt, optional groundtruth.txt); "
                 "without it the synthetic scene plays");
  args.addOption("camera", "FILE", "camera YAML; default: DIR/camera.yaml, else chosen by the folder name");
  args.addOption("synthetic-config", "FILE", "synthetic scene YAML (default: capture.synthetic_config)");
  args.addOption("mode", "MODE", "realtime | fast | lockstep (default: capture.mode)");
  args.addOption("speed", "X", "realtime mode: recorded rate x X (default: capture.speed)");
  args.addOption("start", "N", "first associated frame to play", "0");
  args.addOption("end", "N", "one past the last frame to play; -1 = all", "-1");
  args.addOption("every", "K", "play every K-th frame", "1");
  args.addOption("verify", "HOW", "header | decode: how images are checked before publishing");
  args.addOption("ack-channels", "LIST",
                 "lockstep: comma-separated channels that must all answer a frame "
                 "before the next (default: capture.ack_channels)");
  args.addOption("groundtruth-out", "FILE", "write the ground truth of the played sequence (TUM format)");
  args.addOption("masks-out", "DIR", "synthetic scene: write the dynamic-object masks as PNG");
  args.addOption("loop", "N",
                 "play the source N times as one stream: stamps offset by the sequence's duration each pass, "
                 "seq continuing (long runs)",
                 "1");
  args.addOption("wait-for", "NAMES",
                 "comma-separated process names whose heartbeat must be seen before "
                 "the first frame (e.g. bmp-tracker,bmp-detector)");
  args.addEpilog(
      "Examples:\n"
      "  bmp-capture --dataset ../shared/data/rgbd_bonn_crowd --mode realtime\n"
      "  bmp-capture --mode lockstep --groundtruth-out out/gt.txt      # synthetic scene\n"
      "Skipped files (missing, corrupt, wrong size) are reported with the reason and counted.\n");
}

CaptureSettings readCaptureSettings(const Config& section, const ArgParser& args,
                                    const std::string& config_dir) {
  namespace fs = std::filesystem;
  const Checker check(section, args);
  CaptureSettings s;
  readPlayerOptions(section, args, check, s.player);
  s.max_association_difference_s =
      section.get<double>("max_association_difference_s", s.max_association_difference_s);
  check(s.max_association_difference_s > 0, "max_association_difference_s", "", "must be positive");
  const std::string verify = overridden(section, args, "verify", "verify", toString(s.verify));
  check(parses(parseVerifyMode, verify, s.verify), "verify", "verify",
        "must be header or decode, got '" + verify + "'");
  s.wait_timeout_s = section.get<double>("wait_timeout_s", s.wait_timeout_s);
  check(s.wait_timeout_s > 0, "wait_timeout_s", "", "must be positive");
  const std::string synthetic = section.get<std::string>("synthetic_config", s.synthetic_config);
  check(!synthetic.empty(), "synthetic_config", "", "must name a file");
  s.synthetic_config = args.given("synthetic-config") ? args.value("synthetic-config")
                                                      : (fs::path(config_dir) / synthetic).string();
  s.dataset = args.value("dataset");
  s.camera = args.value("camera");
  s.cameras_dir = (fs::path(config_dir) / "cameras").string();
  readSelection(args, check, s.selection);
  s.groundtruth_out = args.value("groundtruth-out");
  s.wait_for = args.list("wait-for");
  const long long loops = args.integer("loop");
  check(loops >= 1 && loops <= 1000000, "", "loop", "must be between 1 and 1000000");
  s.loops = static_cast<int>(loops);
  return s;
}

}  // namespace bmp::capture

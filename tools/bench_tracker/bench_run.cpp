#include "bench_run.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <random>
#include <stdexcept>
#include <thread>

#include "bmp/common/arg_range.hpp"
#include "bmp/common/config.hpp"
#include "bmp/common/config_dir.hpp"
#include "bmp/common/memory_usage.hpp"
#include "bmp/common/output_path.hpp"
#include "capture/camera_selection.hpp"
#include "capture/looped_source.hpp"
#include "capture/tum_sequence.hpp"
#include "detector/detector.hpp"
#include "detector/detector_settings.hpp"
#include "eval/ate.hpp"
#include "tracker/frame_log.hpp"
#include "tracker/stand_in_boxes.hpp"
#include "tracker/tracker_settings.hpp"
#include "tracker_offline/keypoint_score.hpp"
#include "tracker_offline/offline_runner.hpp"

namespace bmp::tracker {

namespace {

// --config's `tracker` section (built-in defaults when --config is empty); --inline-mapping on top.
TrackerConfig loadConfig(const bmp::ArgParser& args) {
  TrackerConfig config;
  if (!args.value("config").empty()) {
    const bmp::Config file = bmp::Config::fromFile(args.value("config"));
    // Read as bmp-tracker reads it, so the file that runs the process runs the benchmark; the `process`
    // section (channels, queue) is checked and then unused here, as the benchmark has no LCM side.
    config = trackerSettingsFromConfig(file).tracker;
    file.finish();
  }
  if (args.flag("inline-mapping")) config.mapping.threaded = false;
  applyDynamicModeOption(args, config);
  return config;
}

constexpr long long kMaxIntOption = std::numeric_limits<int>::max();

// --frames N, or -1: every frame (a negative N is refused, not taken as "every frame"; 0 frames would time
// nothing and print "nan").
int maxFrames(const bmp::ArgParser& args) {
  return args.given("frames") ? static_cast<int>(bmp::integerIn(args, "frames", 1, kMaxIntOption)) : -1;
}

// --start N: frames skipped from the start of the folder.
int startFrame(const bmp::ArgParser& args) {
  return static_cast<int>(bmp::integerIn(args, "start", 0, kMaxIntOption));
}

std::chrono::milliseconds frameGap(const bmp::ArgParser& args) {
  return std::chrono::milliseconds(bmp::integerIn(args, "frame-gap-ms", 0, kMaxIntOption));
}

// Progress every 100th frame (every frame with --verbose), then the --frame-gap-ms pause.
OfflineOptions offlineOptions(const bmp::ArgParser& args) {
  OfflineOptions options;
  options.max_frames = maxFrames(args);
  const bool verbose = args.flag("verbose");
  // A pause after each frame, as between frames of the pipeline: local mapping then has time to finish
  // (the pipeline's lockstep leaves it idle when the next frame arrives), which changes its timing.
  const auto gap = frameGap(args);
  options.exclude_movers = args.flag("oracle-masks");
  options.on_result = [verbose, gap](const TrackResult& r, const OfflineFrame&) {
    if (gap.count() > 0) std::this_thread::sleep_for(gap);
    if (verbose || r.seq % 100 == 0)
      std::fprintf(stderr, "frame %5lld %-12s kp %4d excluded %4d tracked %4d map %6d kfs %4d  %.1f ms\n",
                   static_cast<long long>(r.seq), toString(r.state), r.num_keypoints, r.num_excluded,
                   r.num_tracked, r.num_map_points, r.num_keyframes, r.processing_ms);
  };
  return options;
}

// Per-frame figures kept while tracking (the frames' results are not kept: long runs measure memory).
struct FrameTimes {
  bmp::TimingStats extract, wait, dynamic;
  bmp::TimingStats position_std_mm;  // tracked frames whose inliers determine the pose
};

// --score-masks: the dynamic stage against DIR/mask/ from this many seconds into the sequence on (the
// probabilities need a few frames of history, as in the scenario tests).
constexpr double kScoreFromS = 1.0;
struct MaskScore {
  KeypointScore score;
  MaskPixelScore keyframe_masks;
  std::optional<double> first_stamp;
};

void printMaskScore(const MaskScore& s) {
  // "n/a" for a share of nothing (no keypoint on a mover, none kept out): tools/bench reads it as no score.
  std::printf("dynamic recall    %s (keypoints on movers kept out)\n", shareText(s.score.recall()).c_str());
  std::printf("dynamic precision %s (keypoints kept out that are on movers)\n",
              shareText(s.score.precision()).c_str());
  std::printf("static kept out   %s\n", shareText(s.score.staticKeptOut()).c_str());
  std::printf("missed on movers  %ld outside every moving region, %ld inside one (history held them)\n",
              s.score.missedOutsideRegions(), s.score.missedInsideRegions());
  std::printf("static out        %ld inside a moving region, %ld by history alone\n",
              s.score.staticOutInsideRegions(), s.score.staticOutByHistory());
  std::printf("keypoints scored  %ld on movers, %ld static (from %.0f s on)\n", s.score.onMovers(),
              s.score.onStatic(), kScoreFromS);
  std::printf("pose inliers on movers %ld of %ld (%s)\n", s.score.moversInPose(), s.score.inPose(),
              shareText(s.score.moversInPoseShare()).c_str());
  std::printf("keyframe masks    movers' pixels %s, static pixels %s masked (%ld keyframes; the mapper's)\n",
              shareText(s.keyframe_masks.moversMasked()).c_str(),
              shareText(s.keyframe_masks.staticMasked()).c_str(), s.keyframe_masks.keyframes());
}

void printRunSummary(const OfflineResult& result, const FrameTimes& times, long long dropped) {
  std::printf("frames           %d\n", result.frames);
  if (dropped > 0) std::printf("frames dropped   %lld (--drop-bursts, not given to the tracker)\n", dropped);
  std::printf("frames tracked   %zu\n", result.trajectory.size());
  std::printf("frames lost      %d%s\n", result.frames_lost, result.lost_at_end ? " (lost at the end)" : "");
  std::printf("keyframes        %zu\n", result.keyframe_trajectory.size());
  std::printf("gap rechecks     %d, %d tracked from the reference keyframe (tracking.recheck_*)\n",
              result.gap_rechecks, result.gap_reference_taken);
  std::printf("track ms median  %.2f\n", result.track_ms.median());
  std::printf("track ms p95     %.2f\n", result.track_ms.p95());
  std::printf("track ms mean    %.2f\n", result.track_ms.mean());
  std::printf("map lock wait ms median %.2f, p95 %.2f (part of track)\n", times.wait.median(),
              times.wait.p95());
  std::printf("extract ms median %.2f (ORB + undistortion + depth, part of track)\n", times.extract.median());
  std::printf("dynamic ms median %.2f, p95 %.2f (the dynamic stage, part of track)\n", times.dynamic.median(),
              times.dynamic.p95());
  if (!times.position_std_mm.empty())
    std::printf("position std mm  median %.1f, p95 %.1f, max %.1f (how well each frame's inliers pin it)\n",
                times.position_std_mm.median(), times.position_std_mm.p95(), times.position_std_mm.max());
}

// Each associated frame's position error after the global alignment: where the trajectory went wrong.
void writeErrors(const std::string& path, const bmp::eval::AteResult& ate) {
  FILE* out = std::fopen(path.c_str(), "w");
  if (out == nullptr) throw std::runtime_error("cannot write " + path);
  for (const auto& pair : ate.pairs) std::fprintf(out, "%.6f %.4f\n", pair.est_stamp, pair.error);
  std::fclose(out);
}

// The ATE, printed; empty when there is none.
std::optional<bmp::eval::AteResult> printAte(const bmp::Trajectory& estimate,
                                             const bmp::Trajectory& groundtruth) {
  if (groundtruth.empty() || estimate.size() < 3) {
    std::printf("ATE              n/a (no ground truth or too few poses)\n");
    return std::nullopt;
  }
  const bmp::eval::AteResult ate = bmp::eval::computeAte(groundtruth, estimate);
  std::printf("ATE rmse m       %.4f\n", ate.stats.rmse);
  std::printf("ATE mean m       %.4f\n", ate.stats.mean);
  std::printf("ATE median m     %.4f\n", ate.stats.median);
  std::printf("ATE max m        %.4f\n", ate.stats.max);
  std::printf("ATE pairs        %zu\n", ate.pairs.size());
  return ate;
}

// --passes N: the folder played N times as one forward stream (each pass's stamps shifted by the sequence's
// period, as bmp-capture --loop does), the ground truth repeated to match. After each pass a line with the
// map's size and this process's resident memory: the map must stop growing once the room is known.
struct PassedFrames {
  FrameProvider frames;
  bmp::Trajectory groundtruth;
  std::shared_ptr<long long> dropped = std::make_shared<long long>(0);  // by --drop-bursts
};

// --detector: the detector (config/detector.yaml, its model replaced by --detector-model if given) over
// every frame of one pass (at most max_frames, < 0: all), before any tracking, so its time counts nowhere and
// the tracker runs as fast as without it; frame i of each pass gets boxes[i].
std::vector<std::vector<ObjectBox>> detectAll(const std::string& model, const std::string& dir,
                                              const CameraIntrinsics& camera, int start, int max_frames) {
  const bmp::Config file = bmp::Config::fromFile(bmp::configDir() + "/detector.yaml");
  auto settings = bmp::detector::detectorSettingsFromConfig(file, std::nullopt, bmp::configDir());
  file.finish();
  try {
    if (!model.empty()) settings.detector = bmp::detector::withModelPreset(settings.detector, model);
  } catch (const std::invalid_argument& e) {
    throw bmp::ArgError(std::string("--detector-model: ") + e.what());
  }
  std::fprintf(stderr, "detector: %s, %d px input\n", settings.detector.model_path.c_str(),
               settings.detector.input_size);
  bmp::detector::Detector detector(settings.detector, bmp::Config::fromFile(settings.dynamic_classes_path));
  std::vector<std::vector<ObjectBox>> all;
  TumFolderOptions folder;
  folder.start = start;
  folder.warn = false;  // the tracking pass that follows reads the same files and names what it skips
  FrameProvider frames = tumFolderFrames(dir, camera, folder);
  while (max_frames < 0 || static_cast<int>(all.size()) < max_frames) {
    const auto frame = frames();
    if (!frame) break;
    all.push_back(toObjectBoxes(detector.detect(frame->image)));
    if (all.size() % 100 == 0) std::fprintf(stderr, "detector: %zu frames\n", all.size());
  }
  return all;
}

// --box-lag K: frame i is observed with frame i-K's answer standing in for its own (moved on for its age
// with frame i-K-1's, by bmp-tracker's real-time rule), and frame i-K's answer comes late with frame i.
void lagBoxes(OfflineFrame& frame, std::size_t i, std::size_t lag,
              const std::vector<std::vector<ObjectBox>>& all, const std::vector<double>& stamps,
              const DynamicOptions& dynamic) {
  if (lag == 0 || i >= all.size()) return;
  frame.boxes = laggedStandIn(all, stamps, i, lag, dynamic);
  frame.boxes_stand_in = true;
  if (i >= lag) frame.late = OfflineFrame::LateBoxes{static_cast<int>(lag), all[i - lag]};
}

// --drop-bursts P: a real-time tracker that falls behind drops frames, several at a time (its queue's oldest
// give way). Each frame from the second second on starts a burst of 1 to 4 dropped frames with probability P,
// drawn from --drop-seed: the same seed drops the same frames.
class DropBursts {
 public:
  DropBursts(double probability, unsigned seed) : probability_(probability), rng_(seed) {}
  // Whether frame i (index in the pass) is dropped.
  bool drop(std::size_t i) {
    if (left_ > 0) {
      --left_;
      return true;
    }
    if (probability_ <= 0.0 || i < kFirstFrame) return false;
    if (std::uniform_real_distribution<double>(0.0, 1.0)(rng_) >= probability_) return false;
    left_ = std::uniform_int_distribution<int>(0, kMaxBurst - 1)(rng_);
    return true;
  }

 private:
  static constexpr std::size_t kFirstFrame = 30;  // the map's first second is left alone
  static constexpr int kMaxBurst = 4;
  double probability_;
  std::mt19937 rng_;
  int left_ = 0;
};

// --box-lag, checked; --detector-model checked as well, as the other option that only --detector uses.
long long boxLag(const bmp::ArgParser& args, bool detect) {
  const long long lag = args.integer("box-lag");
  // 15 frames is 0.5 s at 30 Hz: the oldest a stand-in may be (stale_box_max_age_s) and as long as a keyframe
  // is held for its late boxes (keyframe_hold_ms).
  if (lag < 0 || lag > 15) throw bmp::ArgError("--box-lag must be between 0 and 15 frames");
  if (lag > 0 && !detect)
    throw bmp::ArgError("--box-lag needs --detector and a dynamic mode other than none");
  if (!args.value("detector-model").empty() && !detect)
    throw bmp::ArgError("--detector-model needs --detector and a dynamic mode other than none");
  return lag;
}

// The period of one pass, from the stamps of the folder read without its images. --start past the end is
// refused here: nothing is read, so nothing is skipped, and "no frame could be read (each skip is named
// above)" would send the reader looking for skips that were never named.
double passPeriod(const std::string& dir, int start) {
  const auto index = bmp::capture::indexSequence(dir);
  if (static_cast<std::size_t>(start) >= index.frames.size())
    throw bmp::ArgError("--start " + std::to_string(start) + " is past the end of " + dir + " (" +
                        std::to_string(index.frames.size()) + " associated frames)");
  return bmp::capture::loopPeriod(index.frames.front().rgb_stamp, index.frames.back().rgb_stamp,
                                  static_cast<int64_t>(index.frames.size()));
}

// detect: --detector given and the dynamic stage on (with mode none the boxes would go unused).
PassedFrames passedFrames(const bmp::ArgParser& args, const CameraIntrinsics& camera,
                          std::shared_ptr<const TrackResult> last, bool detect,
                          const DynamicOptions& dynamic) {
  const std::string dir = args.value("dataset");
  const int start = startFrame(args);
  const long long passes = args.integer("passes");
  if (passes < 1 || passes > 1000) throw bmp::ArgError("--passes must be between 1 and 1000");
  const long long lag = boxLag(args, detect);
  const double drop_p = args.number("drop-bursts");
  if (!(drop_p >= 0.0 && drop_p < 1.0)) throw bmp::ArgError("--drop-bursts must be at least 0 and below 1");
  const long long drop_seed = args.integer("drop-seed");
  if (drop_seed < 0) throw bmp::ArgError("--drop-seed must not be negative");
  // First: it refuses a --start past the end as a usage error naming the folder.
  const double period = passPeriod(dir, start);
  PassedFrames out;
  bmp::Trajectory one_pass;
  TumFolderOptions folder;
  folder.start = start;
  folder.load_masks = args.flag("oracle-masks") || args.flag("score-masks");
  folder.groundtruth = &one_pass;
  FrameProvider first = tumFolderFrames(dir, camera, folder);
  folder.groundtruth = nullptr;
  folder.warn = false;  // the later passes read what the first has named
  for (long long p = 0; p < passes; ++p)
    for (const auto& pose : one_pass) {
      auto shifted = pose;
      shifted.stamp += static_cast<double>(p) * period;
      out.groundtruth.push_back(shifted);
    }
  auto boxes = std::make_shared<const std::vector<std::vector<ObjectBox>>>(
      detect ? detectAll(args.value("detector-model"), dir, camera, start, maxFrames(args))
             : std::vector<std::vector<ObjectBox>>{});
  auto stamps = std::make_shared<std::vector<double>>();
  auto current = std::make_shared<FrameProvider>(std::move(first));
  auto pass = std::make_shared<long long>(0);
  auto in_pass = std::make_shared<std::size_t>(0);
  auto drops = std::make_shared<DropBursts>(drop_p, static_cast<unsigned>(drop_seed));
  // The index of the last frame dropped (one past it; 0: none yet).
  auto last_drop = std::make_shared<std::size_t>(0);
  auto dropped = out.dropped;
  // --frames N counts the folder's frames, dropped or not (the detector answered that many).
  const int max_frames = maxFrames(args);
  auto given = std::make_shared<long long>(0);
  out.frames = [=]() -> std::optional<OfflineFrame> {
    for (;;) {
      if (max_frames >= 0 && *given >= max_frames) return std::nullopt;
      if (auto frame = (*current)()) {
        ++*given;
        frame->stamp += static_cast<double>(*pass) * period;
        if (*in_pass < boxes->size()) frame->boxes = (*boxes)[*in_pass];
        stamps->resize(*in_pass + 1);
        (*stamps)[*in_pass] = frame->stamp;
        lagBoxes(*frame, *in_pass, static_cast<std::size_t>(lag), *boxes, *stamps, dynamic);
        const std::size_t i = (*in_pass)++;
        if (drops->drop(i)) {
          *last_drop = i + 1;
          ++*dropped;
          continue;
        }
        // A late answer names its frame by how many frames back it is: with a drop in between that count
        // is not the tracker's, and the answer belonged to a frame the tracker never saw.
        if (frame->late && *last_drop > 0 && i - (*last_drop - 1) <= static_cast<std::size_t>(lag))
          frame->late.reset();
        return frame;
      }
      *in_pass = 0;
      *last_drop = 0;  // indices start again with the pass
      if (passes > 1)
        std::printf("pass %4lld  keyframes %5d  map points %7d  resident %.1f MiB\n", *pass + 1,
                    last->num_keyframes, last->num_map_points,
                    static_cast<double>(bmp::residentBytes()) / (1 << 20));
      std::fflush(stdout);
      if (++*pass >= passes) return std::nullopt;
      *current = tumFolderFrames(dir, camera, folder);
    }
  };
  return out;
}

}  // namespace

int runBenchTracker(const bmp::ArgParser& args) {
  // The counts checked before the camera and the folder are read (they are read again where used).
  maxFrames(args);
  startFrame(args);
  frameGap(args);
  // And the outputs: a path found unwritable only after tracking the whole sequence lost its results.
  for (const char* option : {"trajectory", "keyframe-trajectory", "errors", "frame-log"})
    bmp::checkOutputOption(args, option);
  // The same camera choice as bmp-capture's: --camera, else DIR/camera.yaml, else by the folder's name.
  const bmp::capture::SequenceCamera selected =
      bmp::capture::selectCamera(args.value("dataset"), args.value("camera"), bmp::configDir() + "/cameras");
  std::fprintf(stderr, "camera from %s (%s)\n", selected.file.c_str(), selected.chosen_by.c_str());
  const TrackerConfig config = loadConfig(args);
  Tracker tracker(selected.intrinsics, config);
  auto last = std::make_shared<TrackResult>();
  const PassedFrames input =
      passedFrames(args, selected.intrinsics, last,
                   args.flag("detector") && config.dynamic.mode != DynamicMode::kNone, config.dynamic);
  OfflineOptions options = offlineOptions(args);
  auto times = std::make_shared<FrameTimes>();
  auto scored = std::make_shared<MaskScore>();
  const bool score = args.flag("score-masks");
  options.keep_results = false;
  const bool verbose = args.flag("verbose");
  std::shared_ptr<FrameLog> frame_log;
  if (args.given("frame-log")) frame_log = std::make_shared<FrameLog>(args.value("frame-log"));
  const bool detect = args.flag("detector") && config.dynamic.mode != DynamicMode::kNone;
  const bool lagged = args.integer("box-lag") > 0;
  auto dropped_seen = std::make_shared<long long>(0);
  options.on_result = [report = options.on_result, last, times, scored, score, verbose, frame_log, detect,
                       lagged, dropped = input.dropped,
                       dropped_seen](const TrackResult& r, const OfflineFrame& f) {
    if (frame_log) {
      const char* boxes = !detect ? "-" : !f.boxes ? "none" : lagged ? "stale" : "own";
      frame_log->append(r, {static_cast<int>(*dropped - *dropped_seen), boxes});
    }
    *dropped_seen = *dropped;
    times->extract.add(r.extract_ms);
    times->wait.add(r.lock_wait_ms);
    times->dynamic.add(r.dynamic_ms);
    if (std::isfinite(r.position_std_m)) times->position_std_mm.add(r.position_std_m * 1000.0);
    report(r, f);
    if (score) {
      if (!scored->first_stamp) scored->first_stamp = f.stamp;
      if (verbose) {
        KeypointScore frame;
        frame.add(r, f.mover_mask);
        std::fprintf(  // beside the frame's progress line
            stderr,
            "          pose inliers on movers %3ld of %3ld, movers' keypoints kept out %3ld of %3ld\n",
            frame.moversInPose(), frame.inPose(), frame.moversOut(), frame.onMovers());
      }
      if (f.stamp - *scored->first_stamp >= kScoreFromS) {
        scored->score.add(r, f.mover_mask);
        if (r.new_keyframe && !r.dynamic_mask.empty())
          scored->keyframe_masks.add(r.dynamic_mask, f.mover_mask);
      }
    }
    *last = r;
  };
  const OfflineResult result = runOffline(tracker, input.frames, options);
  // As bmp-capture, which exits 1 when it published nothing: a benchmark of no frames is no result.
  if (result.frames == 0 && maxFrames(args) != 0)
    throw std::runtime_error(args.value("dataset") + ": no frame could be read (each skip is named above)");
  // The results printed before any file is written: a write that fails anyway must not lose them.
  printRunSummary(result, *times, *input.dropped);
  const auto ate = printAte(result.trajectory, input.groundtruth);
  if (score) printMaskScore(*scored);
  std::fflush(stdout);
  if (args.given("trajectory")) bmp::writeTumTrajectory(args.value("trajectory"), result.trajectory);
  if (args.given("keyframe-trajectory"))
    bmp::writeTumTrajectory(args.value("keyframe-trajectory"), result.keyframe_trajectory);
  if (ate && args.given("errors")) writeErrors(args.value("errors"), *ate);
  return 0;
}

void addBenchTrackerOptions(ArgParser& args) {
  args.addOption("dataset", "DIR", "TUM-format folder (rgb.txt, depth.txt, optional groundtruth.txt)");
  args.addOption("camera", "FILE",
                 "camera YAML (key 'camera'); default: DIR/camera.yaml, else chosen by the folder's name");
  args.addOption("config", "FILE", "tracker YAML (key 'tracker'); empty: built-in defaults",
                 bmp::configDir() + "/tracker.yaml");
  args.addOption("frames", "N", "track at most N frames");
  args.addOption("start", "N", "skip the first N associated frames", "0");
  args.addOption("passes", "N",
                 "play the folder N times, as bmp-capture --loop does (map size and memory after each pass)",
                 "1");
  args.addOption("trajectory", "FILE", "write the frame trajectory (TUM format)");
  args.addOption("keyframe-trajectory", "FILE", "write the keyframe trajectory (TUM format)");
  args.addOption("frame-log", "FILE",
                 "write one tab-separated line per frame, as bmp-tracker --frame-log (frames missed: those "
                 "--drop-bursts dropped before it)");
  args.addOption("errors", "FILE",
                 "write each associated frame's position error after alignment (stamp metres)");
  args.addOption("frame-gap-ms", "N", "sleep N ms after each frame (idle time, as between pipeline frames)",
                 "0");
  args.addFlag("inline-mapping", "run local mapping inline instead of in its thread (deterministic)");
  args.addFlag("detector",
               "give the tracker the detector's boxes (config/detector.yaml), found for every frame before "
               "tracking starts (untimed): the dynamic stage at work, as in a lockstep run");
  args.addOption("detector-model", "NAME",
                 "with --detector: the model instead of detector.yaml's: yolov5n-320, yolov5n-640 (the "
                 "paper's input size; about 3 times the time), yolo-fastest-xl");
  args.addOption(
      "box-lag", "K",
      "with --detector: each frame's own answer comes K frames late, as in real time on a busy "
      "machine; the frame is observed with the answer of the frame K before it, moved on for its age "
      "(bmp-tracker's real-time rule), and its own is applied late to its keyframe (0: every frame "
      "its own, as in lockstep)",
      "0");
  args.addOption("drop-bursts", "P",
                 "drop frames as a real-time tracker that falls behind does: from 1 s on, each frame starts "
                 "a burst of 1 to 4 dropped frames with probability P (0: none)",
                 "0");
  args.addOption("drop-seed", "N", "with --drop-bursts: the seed that chooses the dropped frames", "1");
  args.addOption("dynamic-mode", "MODE", "override tracker.dynamic.mode: none|boxes|paper|depth|geometric");
  args.addFlag("oracle-masks", "exclude keypoints on DIR/mask/*.png (bmp-synth's moving-object masks)");
  args.addFlag("score-masks",
               "score the dynamic stage against DIR/mask/*.png: recall (keypoints on movers kept out), "
               "precision, static keypoints kept out; and the keyframes' dynamic masks (the mapper's), "
               "pixel by pixel");
  args.addFlag("verbose", "print every frame's state, not every 100th");
}

}  // namespace bmp::tracker

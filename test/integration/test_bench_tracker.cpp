// bmp-bench-tracker's scoring of the dynamic stage against bmp-synth's masks (what tools/bench puts in its
// recall / precision column): real detector, real tracker, a rendered scenario with people.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <limits>
#include <regex>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "bmp/common/child_process.hpp"
#include "integration_support.hpp"

namespace bmp {
namespace {

namespace fs = std::filesystem;
using test::binPath;

using test::Outcome;
using test::runCommand;
constexpr double kTimeoutS = 240;  // the detector over 90 frames on a loaded 2-core machine

// The number after `label` in the summary. Missing (or "n/a"): a failure, and NaN, which every comparison
// the tests make fails on too.
double figure(const std::string& output, const std::string& label) {
  std::smatch m;
  if (!std::regex_search(output, m, std::regex(label + R"(\s+([0-9.]+))"))) {
    ADD_FAILURE() << "no figure '" << label << "' in the output";
    return std::numeric_limits<double>::quiet_NaN();
  }
  return std::stod(m[1]);
}

// 90 frames (3 s) of people walking, rendered into the running test's own scratch folder (ctest runs the
// cases as separate processes side by side, so none shares a folder).
fs::path writeScenario() {
  const fs::path folder = test::scratchDir("people_walking") / "seq";
  const Outcome o = runCommand(
      "synth",
      {binPath("bmp-synth"), "--config", test::sourceDir() + "/config/synthetic/people_walking.yaml", "--out",
       folder.string(), "--frames", "90"},
      kTimeoutS);
  EXPECT_EQ(o.status, 0) << o.output;
  return folder;
}

// The tracker's configuration with the keypoint budget spread as the paper's extractor spreads it (boxes
// get their area's share): recall and precision are shares of the keypoints on movers, which the default
// budget makes fewer (tracker.yaml, box_keypoint_share).
fs::path paperSpreadConfig() {
  const fs::path file = test::scratchDir("config") / "tracker.yaml";
  std::ofstream(file) << "tracker:\n  dynamic:\n    box_keypoint_share: 1.0\n";
  return file;
}

Outcome score(const std::string& name, const std::string& mode, const fs::path& folder) {
  return runCommand(
      name,
      {binPath("bmp-bench-tracker"), "--dataset", folder.string(), "--detector", "--inline-mapping",
       "--score-masks", "--dynamic-mode", mode, "--config", paperSpreadConfig().string()},
      kTimeoutS);
}

// The default variant keeps most keypoints on the people out and few static ones; the static variant keeps
// none out, so its recall is 0 and it cannot look good by accident.
TEST(BenchTrackerScore, DepthVariantKeepsPeopleOutAndNoneKeepsNothingOut) {
  const fs::path folder = writeScenario();
  const Outcome depth = score("depth", "depth", folder);
  ASSERT_EQ(depth.status, 0) << depth.output;
  EXPECT_GE(figure(depth.output, "dynamic recall"), 0.6) << depth.output;
  EXPECT_GE(figure(depth.output, "dynamic precision"), 0.6) << depth.output;
  EXPECT_LE(figure(depth.output, "static kept out"), 0.1) << depth.output;
  EXPECT_GE(figure(depth.output, "keypoints scored"), 500) << depth.output;  // on movers, over 2 s
  EXPECT_LT(figure(depth.output, "ATE rmse m"), 0.02) << depth.output;
  const double depth_movers_in_pose = figure(depth.output, "pose inliers on movers");
  EXPECT_GE(depth_movers_in_pose, 0.0) << depth.output;

  const Outcome none = score("none", "none", folder);
  ASSERT_EQ(none.status, 0) << none.output;
  EXPECT_EQ(figure(none.output, "dynamic recall"), 0.0) << none.output;
  EXPECT_EQ(figure(none.output, "static kept out"), 0.0) << none.output;
  // What the stage is for: fewer of the pose's inliers lie on the people (90 against 213 when this was
  // written; without the stage the pose's consensus already rejects many).
  EXPECT_LT(depth_movers_in_pose * 1.5, figure(none.output, "pose inliers on movers")) << none.output;
}

// A mask missing from the folder is an error naming the file, not a frame silently scored as all static.
TEST(BenchTrackerScore, AMissingMaskIsAnErrorNamingIt) {
  const fs::path folder = writeScenario();
  std::vector<fs::path> masks;
  for (const auto& e : fs::directory_iterator(folder / "mask")) masks.push_back(e.path());
  ASSERT_FALSE(masks.empty());
  std::sort(masks.begin(), masks.end());
  const fs::path gone = masks[masks.size() / 2];
  fs::remove(gone);
  const Outcome o = score("missing_mask", "depth", folder);
  EXPECT_NE(o.status, 0) << o.output;
  EXPECT_NE(o.output.find(gone.string()), std::string::npos) << o.output;
}

TEST(BenchTrackerScore, AnUnknownDynamicModeIsAnErrorNamingTheOption) {
  const Outcome o = score("bad_mode", "sometimes", writeScenario());
  EXPECT_NE(o.status, 0) << o.output;
  EXPECT_NE(o.output.find("--dynamic-mode"), std::string::npos) << o.output;
}

// --box-lag emulates late answers from the detector's boxes: without them, or out of range, it is an error
// naming the option, not a run that silently ignores it.
TEST(BenchTrackerScore, ABoxLagWithoutTheDetectorIsAnErrorNamingTheOption) {
  const fs::path folder = writeScenario();
  for (const std::vector<std::string>& extra : {std::vector<std::string>{"--box-lag", "2"},
                                                std::vector<std::string>{"--detector", "--box-lag", "-1"}}) {
    std::vector<std::string> command = {binPath("bmp-bench-tracker"), "--dataset", folder.string(),
                                        "--frames", "5"};
    command.insert(command.end(), extra.begin(), extra.end());
    const Outcome o = runCommand("box_lag", command, kTimeoutS);
    EXPECT_NE(o.status, 0) << o.output;
    EXPECT_NE(o.output.find("--box-lag"), std::string::npos) << o.output;
  }
}

// --detector-model swaps the detector's model for one run (the paper's 640-pixel input against our 320):
// the run says which model found its boxes, and a name it does not know, or the option without --detector,
// is an error naming the option.
TEST(BenchTrackerScore, TheDetectorModelIsTheOneNamed) {
  const fs::path folder = writeScenario();
  const auto bench = [&](std::vector<std::string> extra) {
    std::vector<std::string> command = {
        binPath("bmp-bench-tracker"), "--dataset", folder.string(), "--frames", "10", "--inline-mapping"};
    command.insert(command.end(), extra.begin(), extra.end());
    return runCommand("detector_model", command, kTimeoutS);
  };
  const Outcome full = bench({"--detector", "--detector-model", "yolov5n-640"});
  ASSERT_EQ(full.status, 0) << full.output;
  EXPECT_NE(full.output.find("yolov5n_coco_640.onnx, 640 px input"), std::string::npos) << full.output;
  const Outcome configured = bench({"--detector"});
  ASSERT_EQ(configured.status, 0) << configured.output;
  EXPECT_NE(configured.output.find("yolov5n_coco_320.onnx, 320 px input"), std::string::npos)
      << configured.output;
  for (const std::vector<std::string>& wrong :
       {std::vector<std::string>{"--detector", "--detector-model", "yolov9"},
        std::vector<std::string>{"--detector-model", "yolov5n-640"}}) {
    const Outcome o = bench(wrong);
    EXPECT_NE(o.status, 0) << o.output;
    EXPECT_NE(o.output.find("--detector-model"), std::string::npos) << o.output;
  }
}

// --drop-bursts drops frames as a real-time tracker that falls behind does, on the real Bonn frames: every
// frame is either tracked or counted dropped, the same seed drops the same frames (a rare real-time failure
// becomes one that can be run again), and the tracker keeps tracking across the gaps.
TEST(BenchTrackerDrops, TheSameSeedDropsTheSameFramesAndTrackingGoesOn) {
  constexpr int kFrames = 120;
  const std::string frame_log = (test::scratchDir("drops") / "frames.tsv").string();
  const auto run = [&](const std::string& seed) {
    return runCommand(
        "drops_" + seed,
        {binPath("bmp-bench-tracker"), "--dataset", test::bonnDir(), "--frames", std::to_string(kFrames),
         "--inline-mapping", "--drop-bursts", "0.15", "--drop-seed", seed, "--frame-log", frame_log},
        kTimeoutS);
  };
  const Outcome a = run("3");
  ASSERT_EQ(a.status, 0) << a.output;
  const double dropped = figure(a.output, "frames dropped");
  EXPECT_GT(dropped, 0.0) << a.output;
  EXPECT_EQ(figure(a.output, "frames") + dropped, kFrames) << a.output;
  // The frame log has a line per frame tracked, and the frames it says were missed before them are the
  // dropped ones (each burst before the frame after it, each longer than a frame's period).
  int lines = 0, missed = 0, after_gap = 0;
  for (const auto& f : test::readTsvRows(frame_log)) {
    ASSERT_EQ(f.size(), 22u);
    ++lines;
    missed += std::stoi(f[14]);
    if (std::stoi(f[14]) > 0) {
      ++after_gap;
      EXPECT_GT(std::stod(f[13]), 60.0) << "seq " << f[1];  // since the last frame, ms: at least two periods
    }
  }
  EXPECT_EQ(lines, figure(a.output, "frames")) << a.output;
  EXPECT_EQ(missed, dropped) << a.output;
  EXPECT_GT(after_gap, 0);
  EXPECT_EQ(figure(a.output, "frames lost"), 0.0) << a.output;
  EXPECT_LT(figure(a.output, "ATE max m"), 0.10) << a.output;
  const Outcome again = run("3");
  ASSERT_EQ(again.status, 0) << again.output;
  EXPECT_EQ(figure(again.output, "frames dropped"), dropped) << again.output;
  EXPECT_EQ(figure(again.output, "ATE rmse m"), figure(a.output, "ATE rmse m")) << again.output;
}

// Bonn's first 300 frames, inline, the detector's boxes each box_lag frames late, frames dropped with
// drop_seed (seed 2: a burst falls in the fast turn at 5.5 s).
Outcome runTurn(const std::string& name, const std::string& box_lag, const std::string& drop_seed = "2") {
  return runCommand(
      name,
      {binPath("bmp-bench-tracker"), "--dataset", test::bonnDir(), "--frames", "300", "--inline-mapping",
       "--detector", "--box-lag", box_lag, "--drop-bursts", "0.1", "--drop-seed", drop_seed},
      kTimeoutS);
}

// bmp-bench-tracker's "gap rechecks N, M tracked from the reference keyframe": {N, M}; {-1, -1} if absent.
std::pair<int, int> gapChecks(const std::string& output) {
  std::smatch m;
  if (!std::regex_search(output, m, std::regex(R"(gap rechecks\s+(\d+), (\d+) tracked from the reference)")))
    return {-1, -1};
  return {std::stoi(m[1]), std::stoi(m[2])};
}

// Answers 3 frames late: after the burst the constant-velocity guess keeps 14 of the last frame's 525 tracked
// points; the reference keyframe's matches keep 90 and their pose, searched around again, takes over
// (tracking.recheck_*, on by default). In threaded runs such a guess has led the tracker 30 cm astray; here
// (inline mapping, reproducible) the check must happen, take the reference keyframe's pose once, and the
// frames stay within 6 cm (5.2 measured; 3.2 with the check off). Since 2ccad10 (a late answer replaces
// its frame's stand-in) seed 2's guess after that burst is close enough that the check keeps it (1 check,
// none taken, 2.6 cm at worst); seed 7 had a guess the check replaced until b677dbf (fusion leaves dynamic
// keypoints alone) changed the map; seed 4 has one now (4 checks, 1 taken, 2.6 cm at worst).
TEST(BenchTrackerDrops, AGuessFarOffAfterAGapIsCheckedAgainstTheReferenceKeyFrame) {
  const Outcome o = runTurn("drops_turn", "3", "4");
  ASSERT_EQ(o.status, 0) << o.output;
  const auto [checked, taken] = gapChecks(o.output);
  EXPECT_GE(checked, 1) << o.output;
  EXPECT_EQ(taken, 1) << o.output;
  EXPECT_EQ(figure(o.output, "frames lost"), 0.0) << o.output;
  EXPECT_LT(figure(o.output, "ATE max m"), 0.06) << o.output;
  EXPECT_LT(figure(o.output, "ATE rmse m"), 0.02) << o.output;
}

// Every answer on time: with the check off the guess after the burst keeps 17 points, the local map follows
// it 46 cm astray (71 inliers, 163 outliers), a keyframe made there holds the error, and the 300 frames end
// at 21 cm ATE, 41 cm at worst. With the check, as by default, 1.3 cm and 3.7 cm.
TEST(BenchTrackerDrops, ABurstOfDroppedFramesInTheFastTurnDoesNotSendTheTrackerAstray) {
  const Outcome o = runTurn("drops_turn_on_time", "0");
  ASSERT_EQ(o.status, 0) << o.output;
  EXPECT_GE(gapChecks(o.output).second, 1) << o.output;
  EXPECT_EQ(figure(o.output, "frames lost"), 0.0) << o.output;
  EXPECT_LT(figure(o.output, "ATE max m"), 0.08) << o.output;
  EXPECT_LT(figure(o.output, "ATE rmse m"), 0.02) << o.output;
}

TEST(BenchTrackerDrops, AProbabilityOutOfRangeIsAnErrorNamingTheOption) {
  for (const char* p : {"1", "-0.1", "often"}) {
    const Outcome o = runCommand(
        "drop_range",
        {binPath("bmp-bench-tracker"), "--dataset", test::bonnDir(), "--frames", "5", "--drop-bursts", p},
        kTimeoutS);
    EXPECT_NE(o.status, 0) << o.output;
    EXPECT_NE(o.output.find("--drop-bursts"), std::string::npos) << o.output;
  }
}

// A negative count is a usage error naming the option (exit 2), checked before any frame is read:
// --frames -3 once tracked every frame, and --frames 0 read the whole folder to print "nan".
TEST(BenchTrackerOptions, NegativeCountsAreUsageErrorsNamingTheOption) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"--frames", "-3"}, {"--frames", "0"}, {"--start", "-3"}, {"--frame-gap-ms", "-3"}};
  for (const auto& [option, value] : cases) {
    const Outcome o = runCommand(
        "negative", {binPath("bmp-bench-tracker"), "--dataset", test::bonnDir(), option, value}, kTimeoutS);
    EXPECT_EQ(o.status, 2) << option << ": " << o.output;
    const std::string range =
        option == "--frames" ? " must be an integer from 1 to " : " must be an integer from 0 to ";
    EXPECT_NE(o.output.find(option + range), std::string::npos) << o.output;
    EXPECT_NE(o.output.find("got '" + value + "'"), std::string::npos) << o.output;
    EXPECT_EQ(o.output.find("skipped"), std::string::npos) << o.output;  // refused before the folder is read
  }
}

// --start past the end reads nothing, so nothing was skipped: it is said as such, not as "no frame could be
// read (each skip is named above)".
TEST(BenchTrackerOptions, AStartPastTheEndIsSaidAsSuch) {
  const Outcome o =
      runCommand("start_past_end",
                 {binPath("bmp-bench-tracker"), "--dataset", test::bonnDir(), "--start", "1000"}, kTimeoutS);
  EXPECT_EQ(o.status, 2) << o.output;
  EXPECT_NE(o.output.find("--start 1000 is past the end of " + test::bonnDir()), std::string::npos)
      << o.output;
  EXPECT_EQ(o.output.find("each skip is named above"), std::string::npos) << o.output;
}

// A folder that does not exist is said to be missing, not "cannot tell which camera recorded this folder".
TEST(BenchTrackerOptions, AMissingFolderIsSaidToBeMissing) {
  const std::string missing = (test::scratchDir("missing") / "no_such_run").string();
  const Outcome o =
      runCommand("missing_folder", {binPath("bmp-bench-tracker"), "--dataset", missing}, kTimeoutS);
  EXPECT_NE(o.status, 0) << o.output;
  EXPECT_NE(o.output.find(missing + ": no such sequence folder"), std::string::npos) << o.output;
}

// An output that cannot be written is refused before the run: found after tracking the whole sequence, it
// lost every result.
TEST(BenchTrackerOptions, AnUnwritableOutputIsRefusedBeforeTracking) {
  const std::string missing = (test::scratchDir("unwritable") / "no_such_folder").string();
  for (const char* option : {"--trajectory", "--keyframe-trajectory", "--errors", "--frame-log"}) {
    const Outcome o = runCommand(
        "unwritable",
        {binPath("bmp-bench-tracker"), "--dataset", test::bonnDir(), option, missing + "/t.txt"}, kTimeoutS);
    EXPECT_EQ(o.status, 2) << option << ": " << o.output;
    EXPECT_NE(o.output.find(std::string(option) + " '" + missing + "/t.txt': no such folder"),
              std::string::npos)
        << o.output;
    EXPECT_EQ(o.output.find("frames tracked"), std::string::npos) << o.output;
  }
}

// The benchmark reads folders as bmp-capture does: a camera file that does not fit the images skips every
// frame, each named, and a run of no frames is an error naming the folder (as capture exits 1), not a
// summary of zeros.
TEST(BenchTrackerReader, AFolderWithNoReadableFrameIsAnErrorNamingIt) {
  const fs::path camera = test::scratchDir("camera") / "small.yaml";
  std::ifstream bonn(test::sourceDir() + "/config/cameras/bonn.yaml");
  std::stringstream text;
  text << bonn.rdbuf();
  std::ofstream(camera) << std::regex_replace(
      std::regex_replace(text.str(), std::regex("width: 640"), "width: 320"), std::regex("height: 480"),
      "height: 240");
  const Outcome o = runCommand("no_frame",
                               {binPath("bmp-bench-tracker"), "--dataset", test::bonnDir(), "--camera",
                                camera.string(), "--frames", "5"},
                               kTimeoutS);
  EXPECT_EQ(o.status, 1) << o.output;
  EXPECT_NE(o.output.find(test::bonnDir() + ": no frame could be read"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("image is 640x480, the camera is 320x240"), std::string::npos) << o.output;
}

}  // namespace
}  // namespace bmp

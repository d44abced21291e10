// The dynamic stage on a synthetic scenario, with the real detector (YOLOv5n on the rendered frames) and
// the tracker in reproducible mode (mapping inline), scored against the scene's per-mover masks.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <memory>
#include <string>

#include "../capture_synthetic/scenario_test_util.hpp"
#include "bmp/common/config.hpp"
#include "bmp/common/timing.hpp"
#include "detector/detector.hpp"
#include "eval/ate.hpp"
#include "tracker/stand_in_boxes.hpp"
#include "tracker/tracker.hpp"

namespace bmp::tracker {
namespace {

constexpr int kFrames = 240;  // 8 s: every scenario's event happens in it

struct Score {
  double ate = 0.0;
  int lost = 0;
  int keyframes = 0;                     // made (the mapper may cull some later)
  long known_on = 0, known_out = 0;      // keypoints on movers the detector knows (people), kept out
  long still_on = 0, still_out = 0;      // of those, on a person standing still
  long unknown_on = 0, unknown_out = 0;  // on the unknown mover (a textured box)
  long static_on = 0, static_out = 0;    // on the static scene
  // Each tracked frame's position std (TrackResult::position_std_m), with over half the view on movers and
  // with less than a tenth (after the first second).
  TimingStats position_std_covered, position_std_clear;
  // NaN over no keypoints at all: every bound the tests check then fails, as it should (nothing was scored).
  double recall(long out, long on) const {
    return on > 0 ? static_cast<double>(out) / on : std::numeric_limits<double>::quiet_NaN();
  }
};

using BoxesPerFrame = std::vector<std::vector<ObjectBox>>;

// The detector's boxes for every frame, found by the named model (detector::modelPresets()), or by the
// default one (DetectorConfig{}, as config/detector.yaml has it) when model is empty.
BoxesPerFrame detections(const capture::SyntheticScene& scene, const std::string& model) {
  const detector::DetectorConfig base;
  detector::Detector yolo(model.empty() ? base : detector::withModelPreset(base, model),
                          Config::fromFile(test::sourceDir() + "/config/dynamic_classes.yaml"));
  BoxesPerFrame all;
  for (int i = 0; i < kFrames; ++i) all.push_back(toObjectBoxes(yolo.detect(scene.render(i).bgr)));
  return all;
}

void count(const TrackResult& r, const capture::SyntheticFrame& f, Score& s) {
  for (std::size_t k = 0; k < r.keypoints.size(); ++k) {
    const cv::Point p(cvRound(r.keypoints[k].x), cvRound(r.keypoints[k].y));
    if (p.x < 0 || p.y < 0 || p.x >= f.mover_ids.cols || p.y >= f.mover_ids.rows) continue;
    const int id = f.mover_ids.at<uint8_t>(p);
    const bool out = r.keypoint_dynamic[k] != 0;
    if (id == 0) {
      ++s.static_on;
      s.static_out += out;
    } else if (const capture::MoverInfo& m = f.movers.at(static_cast<std::size_t>(id - 1));
               m.kind == capture::MoverKind::kPerson) {
      ++s.known_on;
      s.known_out += out;
      s.still_on += !m.moving;
      s.still_out += !m.moving && out;
    } else {
      ++s.unknown_on;
      s.unknown_out += out;
    }
  }
}

// Real time on a busy machine, reproducibly: every answer comes box_lag frames after its frame, so each
// frame is observed with the stand-in bmp-tracker would use (the answer box_lag frames before, moved on for
// its age when move_stand_ins) and takes its own answer late (applied to its keyframe, if it made one).
struct Lag {
  int frames = 0;  // 0: every frame its own answer, as in lockstep
  bool move_stand_ins = true;
};

// What a test changes in the scene or the tracker beyond the variant (none by default).
using Adjust = std::function<void(capture::SyntheticSceneConfig&, TrackerConfig&)>;

// box_keypoint_share 1: the keypoint budget spread as the paper's extractor spreads it, so that the shares
// of keypoints kept out compare with the paper's (the default budget puts fewer keypoints on people).
// The detector is the default one (320 px) unless detector_model names another.
Score run(const std::string& scenario, DynamicMode mode, double box_keypoint_share = 1.0, Lag lag = {},
          const Adjust& adjust = {}, const std::string& detector_model = "") {
  capture::SyntheticSceneConfig sc = test::scenarioConfig(scenario);
  sc.num_frames = kFrames;
  TrackerConfig config;
  config.mapping.threaded = false;  // reproducible
  config.dynamic.mode = mode;
  config.dynamic.box_keypoint_share = box_keypoint_share;
  if (!lag.move_stand_ins) config.dynamic.stale_box_motion_iou = 0.0;
  if (adjust) adjust(sc, config);
  const capture::SyntheticScene scene(sc);
  const BoxesPerFrame boxes =
      mode == DynamicMode::kNone ? BoxesPerFrame(kFrames) : detections(scene, detector_model);
  Tracker tracker(scene.camera(), config);
  std::vector<double> stamps;
  Score s;
  Trajectory trajectory;
  for (int i = 0; i < kFrames; ++i) {
    const capture::SyntheticFrame f = scene.render(i);
    TrackerInput in;
    in.stamp = f.stamp;
    in.seq = i;
    in.image = f.bgr;
    in.depth = f.depth;
    in.boxes = boxes[static_cast<std::size_t>(i)];
    stamps.push_back(f.stamp);
    if (lag.frames > 0) {
      const auto at = static_cast<std::size_t>(i), back = static_cast<std::size_t>(lag.frames);
      in.boxes = laggedStandIn(boxes, stamps, at, back, config.dynamic);
      in.boxes_stand_in = true;
      if (at >= back) tracker.applyLateBoxes(i - lag.frames, boxes[at - back]);
    }
    const TrackResult r = tracker.track(in);
    s.lost += r.state == TrackingState::kLost;
    s.keyframes += r.new_keyframe.has_value();
    if (i >= 30) count(r, f, s);  // after the first second: the probabilities need a few frames of history
    if (i >= 30 && std::isfinite(r.position_std_m)) {
      const double covered = static_cast<double>(cv::countNonZero(f.mover_ids)) / f.mover_ids.total();
      if (covered > 0.5) s.position_std_covered.add(r.position_std_m);
      if (covered < 0.1) s.position_std_clear.add(r.position_std_m);
    }
  }
  tracker.finish();
  s.ate = eval::computeAte(scene.groundTruth(), tracker.trajectory()).stats.rmse;
  std::printf(
      "%-14s %-9s share %.2f lag %d%s ATE %.2f mm, lost %d, keyframes %d; kept out: people %.1f %% of %ld, "
      "unknown %.1f %% of %ld, static %.1f %% of %ld; people standing still %.1f %% of %ld\n",
      scenario.c_str(), toString(mode), box_keypoint_share, lag.frames,
      lag.move_stand_ins ? "" : " (unmoved)", s.ate * 1000, s.lost, s.keyframes,
      100 * s.recall(s.known_out, s.known_on), s.known_on, 100 * s.recall(s.unknown_out, s.unknown_on),
      s.unknown_on, 100 * s.recall(s.static_out, s.static_on), s.static_on,
      100 * s.recall(s.still_out, s.still_on), s.still_on);
  if (!s.position_std_covered.empty())
    std::printf(
        "  position std median / p95 %.1f / %.1f mm in %zu frames over half covered, %.1f / %.1f mm in "
        "%zu under a tenth\n",
        s.position_std_covered.median() * 1000, s.position_std_covered.p95() * 1000,
        s.position_std_covered.count(), s.position_std_clear.median() * 1000,
        s.position_std_clear.p95() * 1000, s.position_std_clear.count());
  return s;
}

// The default variant's bar: most keypoints on people kept out, few static ones, nothing lost.
void expectPeopleKeptOut(const Score& s, double max_ate) {
  EXPECT_GE(s.recall(s.known_out, s.known_on), 0.80);
  EXPECT_LE(s.recall(s.static_out, s.static_on), 0.05);
  EXPECT_LT(s.ate, max_ate);
  EXPECT_EQ(s.lost, 0);
}

// People the detector knows, walking through the view: the depth variant (boxes cut to the person by
// depth, Bayesian probability) keeps most of their keypoints out and few static ones, and the trajectory
// within 5 mm. (The default, geometric, gave 5.3 mm here against depth's 4.5 when it became the default:
// its residual test also puts 2.7 % of static keypoints out.) Without the dynamic stage the graded consensus
// still holds the pose (5.5 mm against 4.5 when this was written; 158 mm before it): the static variant's gap
// shows in the crowd, below.
TEST(DynamicScenario, PeopleWalkingAreKeptOut) {
  expectPeopleKeptOut(run("people_walking", DynamicMode::kDepth), 0.005);
  const Score none = run("people_walking", DynamicMode::kNone);
  EXPECT_EQ(none.known_out + none.static_out, 0);
}

// A crowd covering over half the view for 2 s: depth and the default (geometric) keep it out, and the
// static variant follows it. One run or pair of runs per test, so that each stays well inside the test
// timeout on a loaded 2-core machine (together they took 147 s on a quiet one, and over 300 s beside a build
// and two busy programs).
constexpr double kCrowdMaxAte = 0.03;  // metres: what the variants that keep the crowd out are held to

// With the paper's spread (every keypoint budget the people's) the crowd leaves the pose about 250 static
// keypoints, and around 6.8 s tracking is marginal (17-25 first inliers). Since the depth gate (e84c79f) took
// away the person keypoints that had matched wall points behind them, 5 frames there are lost and the next is
// relocalised (4.42 mm, 88.5 % of people and 1.8 % of static keypoints kept out); before it none were, and
// with a 0.15 gate 20 were: which frames a starved pose loses moves with any change. The default budget loses
// none (the tests below), which is why every variant with boxes has it.
TEST(DynamicScenario, CrowdIsKeptOutByTheDepthVariant) {
  const Score s = run("crowd", DynamicMode::kDepth);
  EXPECT_GE(s.recall(s.known_out, s.known_on), 0.80);
  EXPECT_LE(s.recall(s.static_out, s.static_on), 0.05);
  EXPECT_LT(s.ate, kCrowdMaxAte);
  EXPECT_LE(s.lost, 12) << "at most 5 % of the frames lost (and relocalised) in the crowd";
}

// With the default keypoint budget (person boxes counted at a quarter of their area) the static scene gets
// the keypoints the crowd would take, and the trajectory is better: 7.9 mm against 15.6 when this was written
// (two more seeds: 8.6 against 10.3, 11.2 against 14.6). Since fusion leaves dynamic keypoints alone
// (b677dbf), seeds 1-8 with the paper's spread against the budget (bmp-bench-tracker, inline): 4.0 / 3.0 /
// 4.0 / 8.4 / 25.3 / 11.9 / 8.1 / 4.3 against 3.8 / 3.4 / 4.8 / 7.6 / 8.5 / 9.6 / 4.8 / 4.6 mm: better
// over the seeds, even on the first three. This test ran seed 1 until then; it runs seed 5, where the
// budget makes the difference.
TEST(DynamicScenario, CrowdIsKeptOutByTheDefaultVariantAndItsKeypointBudgetHelps) {
  const Adjust seed5 = [](capture::SyntheticSceneConfig& sc, TrackerConfig&) { sc.seed = 5; };
  const Score geometric = run("crowd", DynamicMode::kGeometric, 1.0, {}, seed5);
  expectPeopleKeptOut(geometric, kCrowdMaxAte);
  const Score budget =
      run("crowd", DynamicMode::kGeometric, TrackerConfig{}.dynamic.box_keypoint_share, {}, seed5);
  EXPECT_LT(budget.ate, 0.012);
  EXPECT_LT(budget.ate, 0.8 * geometric.ate) << "the static scene's keypoints should hold the pose better";
  // What the crowd leaves of the room (a band above the heads, gaps between people) pins the position less
  // well than the room did, and the frame log's position_std_mm says so: its worst frames 14.0 mm against
  // 5.2 (95th percentiles) when this was written.
  ASSERT_FALSE(budget.position_std_covered.empty());
  ASSERT_FALSE(budget.position_std_clear.empty());
  EXPECT_GT(budget.position_std_covered.p95(), 2.0 * budget.position_std_clear.p95());
  EXPECT_LE(budget.recall(budget.static_out, budget.static_on), 0.10);
  EXPECT_EQ(budget.lost, 0);
}

// The paper's variant keeps whole person boxes out, so in the crowd it has few keypoints left and loses
// frames. With the keypoint budget the static scene between the boxes gets more of them, and the variant
// keeps tracking (50 frames lost with the paper's spread, 8 with the budget, when this was written).
TEST(DynamicScenario, ThePapersVariantLosesFewerFramesInTheCrowdWithTheKeypointBudget) {
  const Score spread = run("crowd", DynamicMode::kPaper);
  const Score budget = run("crowd", DynamicMode::kPaper, TrackerConfig{}.dynamic.box_keypoint_share);
  EXPECT_LT(3 * budget.lost, spread.lost) << "the budget should keep the paper's variant tracking";
  EXPECT_LT(budget.ate, kCrowdMaxAte);
  EXPECT_LT(budget.recall(budget.static_out, budget.static_on),
            spread.recall(spread.static_out, spread.static_on));
}

// Without the dynamic stage the crowd carries the pose: over 5 times the 30 mm the variants above are held
// to (428 mm when this was written).
TEST(DynamicScenario, TheStaticVariantFollowsTheCrowd) {
  const Score none = run("crowd", DynamicMode::kNone);
  EXPECT_GT(none.ate, 5.0 * kCrowdMaxAte) << "the static variant should be clearly worse";
}

// A camera at rest (a robot waiting) while the crowd passes in front of it. Each keyframe made from where the
// last one stands adds only the people, and local BA over such near-identical keyframes moved the resting
// camera by up to 3 cm; so none is made while the camera is within 1 cm and 0.5 degrees of its reference
// keyframe. When this was written: 1.6 mm with the rule, 4.8 mm without it (with sensor-like depth noise,
// three seeds: 1.7 / 2.3 / 1.7 against 6.8 / 5.6 / 4.7 mm). When the written trajectory's smoother came:
// 2.0 against 3.7 mm as tracked, 2.0 against 2.5 smoothed (the smoother hides part of the shake).
TEST(DynamicScenario, ACameraAtRestStaysStillWhileTheCrowdPasses) {
  const double share = TrackerConfig{}.dynamic.box_keypoint_share;
  const auto at_rest = [](bool rule) {
    return [rule](capture::SyntheticSceneConfig& sc, TrackerConfig& config) {
      sc.camera_amplitude = {0.0, 0.0, 0.0};
      sc.rotation_amplitude_deg = {0.0, 0.0, 0.0};
      // The keyframes' effect on the poses as tracked: the written trajectory's smoother would hide some.
      config.refine.smoother.accel_sigma = 0.0;
      if (!rule) config.keyframes.still_distance_m = 0.0;
    };
  };
  const Score with_rule = run("crowd", DynamicMode::kGeometric, share, {}, at_rest(true));
  const Score without = run("crowd", DynamicMode::kGeometric, share, {}, at_rest(false));
  EXPECT_LT(with_rule.ate, 0.004);
  EXPECT_LT(with_rule.ate, 0.6 * without.ate) << "keyframes at rest should not move the camera";
  EXPECT_EQ(with_rule.lost, 0);
  EXPECT_GE(with_rule.recall(with_rule.known_out, with_rule.known_on), 0.80);
}

// A person walks in, stands still for 3 s and walks on. The paper's variant (whole boxes, the paper's
// keypoint spread) meets the bar here: 97.8 % of the person's keypoints and 5.7 % of the static ones
// kept out when this was written. The default (geometric, with its keypoint budget) keeps the standing
// person out too: a small residual does not count inside the person's region, so the box's word stands
// (94.4 % of the standing person's keypoints kept out; 65.9 % when it counted, the probability worn down).
TEST(DynamicScenario, APersonWhoStandsStillStaysKeptOut) {
  const Score paper = run("person_stops", DynamicMode::kPaper);
  EXPECT_GE(paper.recall(paper.known_out, paper.known_on), 0.95);
  EXPECT_LE(paper.recall(paper.static_out, paper.static_on), 0.10);
  EXPECT_EQ(paper.lost, 0);
  const Score geometric =
      run("person_stops", DynamicMode::kGeometric, TrackerConfig{}.dynamic.box_keypoint_share);
  ASSERT_GT(geometric.still_on, 500) << "the scenario should show a person standing still";
  EXPECT_GE(geometric.recall(geometric.still_out, geometric.still_on), 0.90);
  expectPeopleKeptOut(geometric, 0.005);
}

// YOLOv5n at 320 px misses a walking person in some frames (a score just under the threshold) and finds
// them again a frame or a few later. Each frame without the box is a static observation for the person's
// keypoints, and keypoints first seen then start at 0.5: both fall under the threshold. Holding a person
// found in two answers in a row (dynamic.held_box_s) keeps more of them out, and no more static keypoints.
// When this was written, the paper's variant with the keypoint budget: people 82.3 % kept out against
// 77.9 %, static 5.3 % against 5.1 %, 3.4 mm both.
TEST(DynamicScenario, PeopleTheDetectorMissesForAFewFramesAreHeld) {
  const Adjust detector_only = [](capture::SyntheticSceneConfig&, TrackerConfig& config) {
    config.dynamic.held_box_s = 0.0;
  };
  const double share = TrackerConfig{}.dynamic.box_keypoint_share;
  const Score held = run("people_walking", DynamicMode::kPaper, share);
  const Score without = run("people_walking", DynamicMode::kPaper, share, {}, detector_only);
  EXPECT_GT(held.recall(held.known_out, held.known_on),
            without.recall(without.known_out, without.known_on) + 0.02)
      << "held boxes should keep more of the people out";
  EXPECT_LE(held.recall(held.static_out, held.static_on),
            without.recall(without.static_out, without.static_on) + 0.01);
  EXPECT_LT(held.ate, 0.005);
  EXPECT_EQ(held.lost, 0);
}

// The paper's variant as printed needs, beyond run()'s box_keypoint_share 1, the detector's boxes alone (no
// held boxes); depth_ratio is the projection search's depth gate (tracking.match_depth_ratio, 0: none).
Adjust paperAsPrinted(double depth_ratio = TrackerConfig{}.tracking.match_depth_ratio) {
  return [depth_ratio](capture::SyntheticSceneConfig&, TrackerConfig& config) {
    config.dynamic.held_box_s = 0.0;
    config.tracking.match_depth_ratio = depth_ratio;
  };
}

// The paper's variant as the paper has it (its keypoint spread, the detector's boxes alone): a person's
// keypoint that took the wall point behind it (the right-image gate barely tells 2 m from 3.5 m at coarse
// levels) took the wall's static history with it, and its box could not lift it over the threshold. With
// tracking.match_depth_ratio such a keypoint matches nothing, starts at 0.5 and its box puts it out. When
// this was written: people 93.0 % kept out against 90.4 %, static 12.7 % against 13.0 %, ATE 3.1 mm
// against 2.2.
TEST(DynamicScenario, APersonsKeypointDoesNotTakeTheWallPointBehindIt) {
  const Score gated = run("people_walking", DynamicMode::kPaper, 1.0, {}, paperAsPrinted());
  const Score ungated = run("people_walking", DynamicMode::kPaper, 1.0, {}, paperAsPrinted(0.0));
  EXPECT_GT(gated.recall(gated.known_out, gated.known_on),
            ungated.recall(ungated.known_out, ungated.known_on) + 0.015);
  EXPECT_LE(gated.recall(gated.static_out, gated.static_on),
            ungated.recall(ungated.static_out, ungated.static_on) + 0.005);
  EXPECT_LT(gated.ate, 0.005);
  EXPECT_EQ(gated.lost, 0);
}

// The paper's variant as printed, with the detector at the paper's input size (YOLOv5 at 640 px; the
// product runs it at 320, a third of the time). The misses left at 320 lie outside every box: people
// entering the view not found yet, and heads cut off. At 640 the boxes find them, and the bar of
// 95 % is met. When this was written, seeds 1 / 2 / 3: people 97.3 / 97.9 / 97.8 % kept out (93.0 / 95.8 /
// 97.8 at 320). Whole boxes also keep the static scene behind a person out: 12.3 / 6.2 / 9.8 % (12.7 /
// 6.3 / 10.5 at 320), over the 10 % on seed 1, which this test runs; the bound below is that
// figure's with a little room, so that more static keypoints kept out still shows.
TEST(DynamicScenario, ThePapersVariantWithThePapersDetectorInputKeepsPeopleOut) {
  const Score paper = run("people_walking", DynamicMode::kPaper, 1.0, {}, paperAsPrinted(), "yolov5n-640");
  EXPECT_GE(paper.recall(paper.known_out, paper.known_on), 0.95);
  EXPECT_LE(paper.recall(paper.static_out, paper.static_on), 0.135);
  EXPECT_LT(paper.ate, 0.005);
  EXPECT_EQ(paper.lost, 0);
}

// Real time: each answer 3 frames (0.1 s) late, every frame observed with a stand-in. The default still
// keeps most of the people out, few static keypoints, and the trajectory within 5 mm; moving the stand-ins on
// at the speed their boxes showed keeps more of the people out than leaving them where they were. When this
// was written: people 79.8 % kept out (84.3 % with every answer on time), static 4.0 %, 3.7 mm; unmoved
// 78.5 %, 5.5 %, 5.6 mm.
TEST(DynamicScenario, PeopleAreKeptOutWhenEveryAnswerComesLate) {
  const Score moved = run("people_walking", DynamicMode::kGeometric, 1.0, Lag{3, true});
  EXPECT_GE(moved.recall(moved.known_out, moved.known_on), 0.75);
  EXPECT_LE(moved.recall(moved.static_out, moved.static_on), 0.05);
  EXPECT_LT(moved.ate, 0.005);
  EXPECT_EQ(moved.lost, 0);
  const Score unmoved = run("people_walking", DynamicMode::kGeometric, 1.0, Lag{3, false});
  EXPECT_GT(moved.recall(moved.known_out, moved.known_on),
            unmoved.recall(unmoved.known_out, unmoved.known_on))
      << "moving stand-ins on should keep more of the people out";
}

// A textured box no detector knows pacing 2.4 m from the camera, over a quarter of the view: the pose must
// follow the room, not the box (250 mm ATE when the consensus counted matches instead of grading them).
// With the geometric observation (keypoints tracked from the last frame over a wide window, judged against
// where each track began, and spread over each moving cluster) most of the box is kept out too: 0.9 % of
// its keypoints were before the tracks.
TEST(DynamicScenario, AnUnknownRigidMoverDoesNotCarryThePose) {
  for (const DynamicMode mode : {DynamicMode::kDepth, DynamicMode::kGeometric}) {
    const Score s = run("unknown_mover", mode);
    EXPECT_LT(s.ate, 0.01) << toString(mode);
    EXPECT_EQ(s.lost, 0) << toString(mode);
    if (mode == DynamicMode::kGeometric) {
      EXPECT_GE(s.recall(s.unknown_out, s.unknown_on), 0.80);
      EXPECT_GE(s.recall(s.known_out, s.known_on), 0.80);
      EXPECT_LE(s.recall(s.static_out, s.static_on), 0.05);
    }
  }
}

// The main job's scene (two textured boxes no detector knows): each keyframe made points on the boxes'
// keypoints, the boxes moved on, the points were not found again and the keypoints called for close
// structure once more, so nearly every frame made a keyframe (keyframes.close_*; 86 in 300 frames, tracking
// p95 173 ms). Waiting close_min_frames frames since the last keyframe gives its points the chance to be
// found again first: 46 keyframes and 5.0 mm against 6.5 on that scene (bmp-bench-tracker, 300 frames). Over
// 21 synthetic sequences (bmp-synth: `crowd` seeds 1-8, `static` 1-3, `people_walking` 1-4, `unknown_mover`
// 1-3, `person_stops` 1-2) the crowd's error went down in 7 of 8 and the others' moved by -0.2 to +0.5 mm.
TEST(DynamicScenario, AMoverTheDetectorDoesNotKnowDoesNotMakeAKeyframeOfEveryFrame) {
  const auto every = [](capture::SyntheticSceneConfig&, TrackerConfig& c) {
    c.keyframes.close_min_frames = 1;
  };
  const Score without = run("boxes", DynamicMode::kGeometric, 0.25, {}, every);
  const Score with = run("boxes", DynamicMode::kGeometric, 0.25);
  EXPECT_EQ(with.lost, 0);
  EXPECT_LT(with.keyframes, 0.7 * without.keyframes);
  EXPECT_LT(with.ate, 1.1 * without.ate);
}

// The trajectory written at the end re-estimates each frame against its own points once its keyframe has
// left local BA (tracker.refine): the error a frame had against the map of its moment goes (people_walking,
// seeds 1-3 with bmp-bench-tracker: 3.9 / 4.5 / 4.1 mm without, 3.0 / 3.4 / 3.6 with; since the depth gate,
// e84c79f, 2.3 / 3.3 / 3.5 without and 2.0 / 2.8 / 2.6 with, ratios 0.87 / 0.85 / 0.74).
TEST(DynamicScenario, EachFramesSecondLookBringsTheTrajectoryCloser) {
  const auto off = [](capture::SyntheticSceneConfig&, TrackerConfig& c) { c.refine.after_keyframes = 0; };
  const Score without = run("people_walking", DynamicMode::kGeometric, 0.25, {}, off);
  const Score with = run("people_walking", DynamicMode::kGeometric, 0.25);
  EXPECT_EQ(with.lost, 0);
  EXPECT_LT(with.ate, 0.92 * without.ate) << without.ate;  // 1.96 against 2.28 mm
}

// A camera shaken as by a hand (config/synthetic/shaken_camera.yaml: people walking, periods of 1-1.6 s,
// 6 m/s^2 median): the written positions are smoothed against the camera's own acceleration, measured from
// its path, not against the 1 m/s^2 floor, which bends its real motion (bmp-synth seeds 1-4: 3.7 / 11.6 /
// 3.9 / 4.2 mm against 5.5 / 13.5 / 5.2 / 6.1 with the floor always, 4.5 / 13.6 / 5.0 / 5.2 unsmoothed).
TEST(DynamicScenario, AShakenCameraIsNotSmoothedAgainstTheFloor) {
  const auto floor_only = [](capture::SyntheticSceneConfig&, TrackerConfig& c) {
    c.refine.smoother.accel_lag_s = 0.0;
  };
  const Score with_floor = run("shaken_camera", DynamicMode::kGeometric, 0.25, {}, floor_only);
  const Score measured = run("shaken_camera", DynamicMode::kGeometric, 0.25);
  EXPECT_EQ(measured.lost, 0);
  EXPECT_LT(measured.ate, 0.8 * with_floor.ate);
  EXPECT_LT(measured.ate, 0.005);
}

// The same shaken camera, tracked: each frame's position is held to the constant-velocity prediction only
// within what this camera's measured acceleration makes it miss by, not within the 9 m/s^2 floor, which
// pulls it off its path (motion_prior.hpp). Inline here, where the map is always ready, the gain is
// smaller; in real time (mapping in its thread) the floor pulled the tracker off for good in most runs.
// Seed 2, where the floor goes wrong inline too: with bmp-bench-tracker at e84c79f, seeds 1-4 gave 3.2 /
// 9.8 / 4.0 / 3.4 mm held to the floor and 2.8 / 3.7 / 3.7 / 2.9 measured (seed 1 was 3.70 against 2.84
// before the depth gate).
TEST(DynamicScenario, AShakenCameraIsNotHeldToTheMotionPriorsFloor) {
  const auto seed2 = [](capture::SyntheticSceneConfig& sc, TrackerConfig&) { sc.seed = 2; };
  const auto floor_only = [](capture::SyntheticSceneConfig& sc, TrackerConfig& c) {
    sc.seed = 2;
    c.pose.motion_prior_accel_lag_s = 0.0;
  };
  const Score with_floor = run("shaken_camera", DynamicMode::kGeometric, 0.25, {}, floor_only);
  const Score measured = run("shaken_camera", DynamicMode::kGeometric, 0.25, {}, seed2);
  EXPECT_EQ(measured.lost, 0);
  EXPECT_LT(measured.ate, 0.85 * with_floor.ate) << with_floor.ate;
  EXPECT_LT(measured.ate, 0.005);
}

}  // namespace
}  // namespace bmp::tracker

// The synthetic scene's configuration, its FrameSource and the TUM folder writer.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "bmp/common/camera_config.hpp"
#include "bmp/common/config.hpp"
#include "bmp/common/image_codec.hpp"
#include "bmp/common/tum_trajectory.hpp"
#include "capture/camera_selection.hpp"
#include "capture/synthetic_config.hpp"
#include "capture/synthetic_geometry.hpp"
#include "capture/synthetic_source.hpp"
#include "capture/tum_folder_writer.hpp"
#include "capture/tum_source.hpp"
#include "shared_data.hpp"

namespace bmp::capture {
namespace {

SyntheticSceneConfig shortSequence(int frames) {
  SyntheticSceneConfig c;
  c.num_frames = frames;
  c.texels_per_metre = 100;  // quicker to build; the geometry is the same
  return c;
}

TEST(SyntheticConfig, ShippedFileIsCompleteAndMatchesTheDefaults) {
  const Config file = Config::fromFile(test::sourceDir() + "/config/synthetic.yaml");
  const SyntheticSceneConfig c = syntheticSceneFromConfig(file.section("synthetic"));
  EXPECT_NO_THROW(file.finish());
  const SyntheticSceneConfig d;
  EXPECT_EQ(c.camera.width, d.camera.width);
  EXPECT_EQ(c.camera.height, d.camera.height);
  EXPECT_EQ(c.camera.fx, d.camera.fx);
  EXPECT_EQ(c.camera.fy, d.camera.fy);
  EXPECT_EQ(c.camera.cx, d.camera.cx);
  EXPECT_EQ(c.camera.cy, d.camera.cy);
  EXPECT_EQ(c.camera.depth_scale, d.camera.depth_scale);
  EXPECT_EQ(c.num_frames, d.num_frames);
  EXPECT_EQ(c.fps, d.fps);
  EXPECT_EQ(c.start_stamp, d.start_stamp);
  EXPECT_EQ(c.seed, d.seed);
  EXPECT_EQ(c.room_size, d.room_size);
  EXPECT_EQ(c.num_static_boxes, d.num_static_boxes);
  EXPECT_EQ(c.texels_per_metre, d.texels_per_metre);
  EXPECT_EQ(c.shapes_per_square_metre, d.shapes_per_square_metre);
  EXPECT_EQ(c.camera_centre, d.camera_centre);
  EXPECT_EQ(c.camera_amplitude, d.camera_amplitude);
  EXPECT_EQ(c.camera_period, d.camera_period);
  EXPECT_EQ(c.base_pitch_deg, d.base_pitch_deg);
  EXPECT_EQ(c.rotation_amplitude_deg, d.rotation_amplitude_deg);
  EXPECT_EQ(c.rotation_period, d.rotation_period);
  EXPECT_EQ(c.scenario, d.scenario);
  EXPECT_EQ(c.num_moving_objects, d.num_moving_objects);
  EXPECT_EQ(c.object_size, d.object_size);
  ASSERT_EQ(c.people.size(), d.people.size());
  for (std::size_t i = 0; i < c.people.size(); ++i) {
    EXPECT_EQ(c.people[i].image, d.people[i].image);
    EXPECT_EQ(c.people[i].rect, d.people[i].rect);
    EXPECT_EQ(c.people[i].height_m, d.people[i].height_m);
  }
  EXPECT_EQ(c.walk_speed, d.walk_speed);
  EXPECT_EQ(c.max_depth, d.max_depth);
  EXPECT_EQ(c.depth_noise, d.depth_noise);
  EXPECT_EQ(c.color_noise, d.color_noise);
  EXPECT_EQ(c.camera_ramp_s, d.camera_ramp_s);
  EXPECT_EQ(c.exposure_s, d.exposure_s);
  EXPECT_EQ(c.exposure_samples, d.exposure_samples);
}

TEST(SyntheticConfig, ReadsOverridesAndRejectsBadValues) {
  const Config ok = Config::fromString(
      "synthetic: {seed: 9, num_moving_objects: 0, room_size: [7, 6, 3.5], camera: {fx: 500}}", "test");
  const SyntheticSceneConfig c = syntheticSceneFromConfig(ok.section("synthetic"));
  EXPECT_EQ(c.seed, 9);
  EXPECT_EQ(c.num_moving_objects, 0);
  EXPECT_EQ(c.room_size[1], 6.0);
  EXPECT_EQ(c.camera.fx, 500.0);
  EXPECT_EQ(c.camera.fy, 525.0);
  const Config short_list = Config::fromString("synthetic: {room_size: [7, 6]}", "test");
  EXPECT_THROW(syntheticSceneFromConfig(short_list.section("synthetic")), ConfigError);
  const Config people = Config::fromString(
      "synthetic: {scenario: crowd, people: {a: {image: /x.png, rect: [1, 2, 30, 60]}}}", "test");
  const SyntheticSceneConfig crowd = syntheticSceneFromConfig(people.section("synthetic"));
  EXPECT_EQ(crowd.scenario, SyntheticScenario::kCrowd);
  ASSERT_EQ(crowd.people.size(), 1u);
  EXPECT_EQ(crowd.people[0].image, "/x.png");
  EXPECT_EQ(crowd.people[0].rect, (std::array<int, 4>{1, 2, 30, 60}));
  EXPECT_EQ(crowd.people[0].height_m, 1.7);
  for (const char* bad :
       {"synthetic: {scenario: parade}", "synthetic: {people: {a: {image: x.png, rect: [1, 2]}}}",
        "synthetic: {people: {a: {rect: [1, 2, 3, 4]}}}",
        "synthetic: {people: {a: {image: x.png, rect: [1, 2, 30, 60], height_m: 9}}}"}) {
    const Config c = Config::fromString(bad, "test");
    EXPECT_THROW(syntheticSceneFromConfig(c.section("synthetic")), ConfigError) << bad;
  }
  SyntheticSceneConfig missing;
  missing.scenario = SyntheticScenario::kPersonStops;
  missing.people = {{"images/no_such_photo.jpg", {0, 0, 40, 80}, 1.7}};
  EXPECT_THROW(SyntheticScene{missing}, std::runtime_error);
  SyntheticSceneConfig tiny;
  tiny.room_size = {2, 2, 2};
  EXPECT_THROW(SyntheticScene{tiny}, std::invalid_argument);
}

// Motion blur: the colour image is smeared along the motion (less fine detail), the depth, masks, pose and
// the image's mean brightness stay the stamp's; a camera at rest is not blurred at all.
// A ramped-in camera starts at rest at the path's centre (the scene starts as a hand-held recording
// usually does) and moves exactly as the unramped one once the ramp is over.
TEST(SyntheticOptions, ARampedCameraStartsAtRestThenMovesAsWithoutTheRamp) {
  SyntheticSceneConfig plain;
  plain.camera_period = {1.5, 1.2, 1.0};
  SyntheticSceneConfig ramped = plain;
  ramped.camera_ramp_s = 1.0;
  const synth::CameraMotion motion = synth::cameraMotion(plain);
  const double dt = 1e-3;
  const Eigen::Vector3d p0 = synth::cameraPoseAt(ramped, motion, 0.0).translation();
  const Eigen::Vector3d p1 = synth::cameraPoseAt(ramped, motion, dt).translation();
  EXPECT_LT((p0 - Eigen::Map<const Eigen::Vector3d>(plain.camera_centre.data())).norm(), 1e-12);
  EXPECT_LT((p1 - p0).norm() / dt, 0.01) << "m/s at the start";
  EXPECT_GT((synth::cameraPoseAt(plain, motion, dt).translation() -
             synth::cameraPoseAt(plain, motion, 0.0).translation())
                    .norm() /
                dt,
            0.1);
  for (double t : {1.0, 1.7, 3.2})
    EXPECT_TRUE(synth::cameraPoseAt(ramped, motion, t).isApprox(synth::cameraPoseAt(plain, motion, t), 1e-12))
        << t;
  ramped.camera_ramp_s = -1.0;
  EXPECT_THROW(SyntheticScene{ramped}, std::invalid_argument);
}

TEST(SyntheticOptions, ExposureBlursTheColourImageOnly) {
  SyntheticSceneConfig sharp = shortSequence(40);
  sharp.color_noise = 0.0;
  sharp.camera_period = {1.5, 1.2, 1.0};  // a shaken camera, so 1/30 s of exposure moves the image
  sharp.rotation_period = {1.6, 1.3, 1.5};
  SyntheticSceneConfig blurred = sharp;
  blurred.exposure_s = 1.0 / 30;
  const SyntheticScene a(sharp), b(blurred);
  auto detail = [](const cv::Mat& bgr) {
    cv::Mat grey, lap;
    cv::cvtColor(bgr, grey, cv::COLOR_BGR2GRAY);
    cv::Laplacian(grey, lap, CV_32F);
    cv::Scalar mean, stddev;
    cv::meanStdDev(lap, mean, stddev);
    return stddev[0];
  };
  const SyntheticFrame fa = a.render(20), fb = b.render(20);
  EXPECT_LT(detail(fb.bgr), 0.8 * detail(fa.bgr));
  EXPECT_NEAR(cv::mean(fb.bgr)[1], cv::mean(fa.bgr)[1], 1.0);
  EXPECT_EQ(cv::norm(fa.depth, fb.depth, cv::NORM_INF), 0);
  EXPECT_EQ(cv::norm(fa.mover_ids, fb.mover_ids, cv::NORM_INF), 0);
  EXPECT_TRUE(fa.T_world_cam.isApprox(fb.T_world_cam));

  SyntheticSceneConfig still = blurred;
  still.camera_amplitude = {0, 0, 0};
  still.rotation_amplitude_deg = {0, 0, 0};
  still.num_moving_objects = 0;
  SyntheticSceneConfig still_sharp = still;
  still_sharp.exposure_s = 0.0;
  EXPECT_LE(
      cv::norm(SyntheticScene(still).render(5).bgr, SyntheticScene(still_sharp).render(5).bgr, cv::NORM_INF),
      1);  // rounding of the mean

  SyntheticSceneConfig too_long = sharp;
  too_long.exposure_s = 0.05;  // longer than a frame at 30 Hz
  EXPECT_THROW(SyntheticScene{too_long}, std::invalid_argument);
}

TEST(SyntheticOptions, NoiseAndRangeBehaveAsConfigured) {
  SyntheticSceneConfig clean = shortSequence(1);
  clean.color_noise = 0.0;
  SyntheticSceneConfig noisy = clean;
  noisy.color_noise = 3.0;
  noisy.depth_noise = 0.004;
  noisy.max_depth = 3.0;
  const SyntheticFrame a = SyntheticScene(clean).render(0);
  const SyntheticFrame b = SyntheticScene(noisy).render(0);
  EXPECT_EQ(cv::norm(a.mask, b.mask, cv::NORM_INF), 0);  // same geometry and texture

  cv::Mat colour_diff;
  cv::subtract(b.bgr, a.bgr, colour_diff, cv::noArray(), CV_32F);
  cv::Scalar mean, stddev;
  cv::meanStdDev(colour_diff.reshape(1), mean, stddev);
  EXPECT_NEAR(mean[0], 0.0, 0.2);
  EXPECT_NEAR(stddev[0], 3.0, 0.4);

  const double scale = clean.camera.depth_scale;
  int cut = 0, kept = 0;
  double sum_sq = 0;
  for (int v = 0; v < a.depth.rows; ++v) {
    for (int u = 0; u < a.depth.cols; ++u) {
      const double za = a.depth.at<uint16_t>(v, u) / scale, zb = b.depth.at<uint16_t>(v, u) / scale;
      ASSERT_GT(za, 0.0);  // the room is closed and within 8 m
      if (zb == 0.0) {
        ++cut;
        continue;
      }
      EXPECT_LE(zb, 3.0);
      sum_sq += std::pow((zb - za) / (0.004 * za * za), 2);
      ++kept;
    }
  }
  EXPECT_GT(cut, 1000);  // beyond max_depth
  ASSERT_GT(kept, 1000);
  EXPECT_NEAR(std::sqrt(sum_sq / kept), 1.0, 0.15);  // noise in units of its sigma
}

TEST(SyntheticSource, DeliversRawFramesWithGroundTruthAndMasks) {
  auto scene = std::make_shared<const SyntheticScene>(shortSequence(3));
  SyntheticSource source(scene);
  EXPECT_EQ(source.size(), 3);
  EXPECT_EQ(source.camera().fx, 525.0);
  for (int i = 0; i < 3; ++i) {
    const auto frame = source.next();
    ASSERT_TRUE(frame.has_value());
    EXPECT_EQ(frame->index, i);
    EXPECT_EQ(frame->color.encoding, ImageEncoding::kRaw);
    EXPECT_EQ(frame->color.pixel_format, PixelFormat::kBgr8);
    EXPECT_EQ(frame->depth.pixel_format, PixelFormat::kMono16);
    const SyntheticFrame expected = scene->render(i);
    EXPECT_EQ(cv::norm(decodeImage(frame->color), expected.bgr, cv::NORM_INF), 0);
    EXPECT_EQ(cv::norm(decodeImage(frame->depth), expected.depth, cv::NORM_INF), 0);
    EXPECT_EQ(frame->dynamic_mask.type(), CV_8UC1);
    ASSERT_TRUE(frame->T_world_cam_true.has_value());
    EXPECT_TRUE(frame->T_world_cam_true->isApprox(expected.T_world_cam));
    EXPECT_EQ(frame->stamp, expected.stamp);
  }
  EXPECT_FALSE(source.next().has_value());
  EXPECT_EQ(source.skips().total(), 0);
}

TEST(SyntheticTumFolder, WritesAFolderThatReadsBack) {
  const SyntheticScene scene(shortSequence(4));
  const std::string dir = test::scratchDir("synthetic_tum").string();
  int calls = 0;
  writeTumFolder(scene, dir, [&](int done, int total) {
    EXPECT_EQ(done, ++calls);
    EXPECT_EQ(total, 4);
  });
  EXPECT_EQ(calls, 4);
  const Trajectory gt = readTumTrajectory(dir + "/groundtruth.txt");
  ASSERT_EQ(gt.size(), 4u);
  std::ifstream rgb_list(dir + "/rgb.txt"), depth_list(dir + "/depth.txt");
  std::string line;
  int listed = 0;
  while (std::getline(rgb_list, line)) listed += (!line.empty() && line[0] != '#') ? 1 : 0;
  EXPECT_EQ(listed, 4);
  for (int i = 0; i < 4; ++i) {
    const SyntheticFrame f = scene.render(i);
    EXPECT_NEAR(gt[i].stamp, f.stamp, 1e-9);
    EXPECT_LT((gt[i].T_world_cam.translation() - f.T_world_cam.translation()).norm(), 1e-6);
    EXPECT_LT(rotationAngle(gt[i].T_world_cam.inverse() * f.T_world_cam), 1e-6);
    char name[64];
    std::snprintf(name, sizeof(name), "%.6f.png", f.stamp);
    const cv::Mat rgb = cv::imread(dir + "/rgb/" + name, cv::IMREAD_UNCHANGED);
    const cv::Mat depth = cv::imread(dir + "/depth/" + name, cv::IMREAD_UNCHANGED);
    const cv::Mat mask = cv::imread(dir + "/mask/" + name, cv::IMREAD_UNCHANGED);
    ASSERT_EQ(rgb.type(), CV_8UC3);
    ASSERT_EQ(depth.type(), CV_16UC1);
    ASSERT_EQ(mask.type(), CV_8UC1);
    EXPECT_EQ(rgb.size(), cv::Size(640, 480));
    EXPECT_EQ(cv::norm(rgb, f.bgr, cv::NORM_INF), 0);
    EXPECT_EQ(cv::norm(depth, f.depth, cv::NORM_INF), 0);
    EXPECT_EQ(cv::norm(mask, f.mask, cv::NORM_INF), 0);
  }
}

// The written folder is an ordinary TUM folder: the capture reader plays it, with the camera it carries.
TEST(SyntheticTumFolder, PlaysThroughTheTumReader) {
  const SyntheticScene scene(shortSequence(5));
  const std::string dir = test::scratchDir("synthetic_tum_play").string();
  writeTumFolder(scene, dir);
  const SequenceCamera selected = selectCamera(dir, "", test::sourceDir() + "/config/cameras");
  ASSERT_EQ(selected.file, dir + "/camera.yaml");
  EXPECT_EQ(selected.chosen_by, "the folder's camera.yaml");
  const CameraIntrinsics& k = selected.intrinsics;
  EXPECT_EQ(k.fx, scene.camera().fx);
  EXPECT_EQ(k.depth_scale, scene.camera().depth_scale);
  TumSource source(indexSequence(dir), k, {});
  int played = 0;
  while (auto frame = source.next()) {
    const SyntheticFrame truth = scene.render(played);
    EXPECT_NEAR(frame->stamp, truth.stamp, 1e-6);
    EXPECT_EQ(cv::norm(decodeImage(frame->depth), truth.depth, cv::NORM_INF), 0);
    ++played;
  }
  EXPECT_EQ(played, 5);
  EXPECT_EQ(source.skips().total(), 0);
}

// --out on an existing folder: a typo naming a recorded sequence must not rewrite its lists, and a rerun
// with --overwrite must not leave the old run's frames behind.
TEST(SyntheticTumFolder, RefusesAFolderThatIsNotEmptyAndReplacesOnlyItsOwn) {
  namespace fs = std::filesystem;
  const fs::path recorded = test::scratchDir("recorded");
  std::ofstream(recorded / "rgb.txt") << "# color images\n1.0 rgb/1.0.png\n";
  EXPECT_THROW(prepareTumFolder(recorded.string(), false), OutputFolderError);
  EXPECT_THROW(prepareTumFolder(recorded.string(), true), OutputFolderError);  // not bmp-synth's rgb.txt
  std::ifstream kept(recorded / "rgb.txt");
  std::string line;
  std::getline(kept, line);
  EXPECT_EQ(line, "# color images");

  const fs::path dir = test::scratchDir("rerun");
  prepareTumFolder(dir.string(), false);  // empty: fine
  writeTumFolder(SyntheticScene(shortSequence(3)), dir.string());
  try {
    prepareTumFolder(dir.string(), false);
    ADD_FAILURE() << "a folder holding a sequence was accepted";
  } catch (const OutputFolderError& e) {
    EXPECT_NE(std::string(e.what()).find(dir.string()), std::string::npos) << e.what();
  }
  prepareTumFolder(dir.string(), true);
  EXPECT_TRUE(fs::is_empty(dir));
  writeTumFolder(SyntheticScene(shortSequence(3)), dir.string());
  std::ofstream(dir / "rgb" / "notes.txt") << "mine\n";  // someone's file inside: refused, kept
  EXPECT_THROW(prepareTumFolder(dir.string(), true), OutputFolderError);
  EXPECT_TRUE(fs::exists(dir / "rgb" / "notes.txt"));
  EXPECT_TRUE(fs::exists(dir / "rgb.txt"));
}

}  // namespace
}  // namespace bmp::capture

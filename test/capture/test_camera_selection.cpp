#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "bmp/common/config.hpp"
#include "capture/camera_selection.hpp"
#include "capture/tum_sequence.hpp"
#include "shared_data.hpp"

namespace bmp::capture {
namespace {

const std::string kCameras = test::sourceDir() + "/config/cameras";

TEST(CameraSelection, BonnFolderGetsTheBonnCamera) {
  const SequenceCamera selected = selectCamera(test::bonnDir(), "", kCameras);
  EXPECT_EQ(selected.file, kCameras + "/bonn.yaml");
  EXPECT_NEAR(selected.intrinsics.fx, 542.822841, 1e-3);  // Bonn RGB-D Dynamic's published intrinsics
  EXPECT_EQ(selected.intrinsics.width, 640);
}

TEST(CameraSelection, ExplicitFileWinsOverTheFolderName) {
  const SequenceCamera selected = selectCamera(test::bonnDir(), kCameras + "/tum_fr1.yaml", kCameras);
  EXPECT_EQ(selected.file, kCameras + "/tum_fr1.yaml");
  EXPECT_NEAR(selected.intrinsics.fx, 517.306408, 1e-6);
}

TEST(CameraSelection, UnknownFolderIsAnErrorNamingIt) {
  const std::string dir = test::scratchDir("camera_unknown").string();
  try {
    selectCamera(dir, "", kCameras);
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find(dir), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("--camera"), std::string::npos) << e.what();
  }
}

// A mistyped folder is said to be missing (as bmp-capture says), not "cannot tell which camera recorded it",
// with or without --camera.
TEST(CameraSelection, AMissingFolderIsSaidToBeMissing) {
  const std::string dir = (test::scratchDir("camera_missing") / "no_such_run").string();
  for (const std::string& camera : {std::string(), kCameras + "/tum_fr1.yaml"}) {
    try {
      selectCamera(dir, camera, kCameras);
      ADD_FAILURE() << "a missing folder was accepted";
    } catch (const SequenceError& e) {
      EXPECT_EQ(std::string(e.what()), dir + ": no such sequence folder");
    }
  }
}

// Only the folder's own name counts: a recording under a parent named after another camera is not taken
// for that camera's (it silently got the wrong intrinsics), and a trailing slash changes nothing.
TEST(CameraSelection, AParentFoldersNameDoesNotChooseTheCamera) {
  const auto parent = test::scratchDir("camera_parent") / "bonn_fr2_tests";
  const std::string dir = (parent / "myrun").string();
  std::filesystem::create_directories(dir);
  EXPECT_EQ(cameraFileFor(dir, kCameras), "");
  EXPECT_THROW(selectCamera(dir, "", kCameras), ConfigError);
  const std::string named = (parent / "rgbd_dataset_freiburg2_desk").string();
  std::filesystem::create_directories(named);
  EXPECT_EQ(cameraFileFor(named + "/", kCameras), kCameras + "/tum_fr2.yaml");
  const SequenceCamera selected = selectCamera(named, "", kCameras);
  EXPECT_NE(selected.chosen_by.find("guessed from the folder's name"), std::string::npos)
      << selected.chosen_by;
}

}  // namespace
}  // namespace bmp::capture

#include <gtest/gtest.h>

#include <string>

#include "bmp/common/config.hpp"
#include "capture/camera_selection.hpp"
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

}  // namespace
}  // namespace bmp::capture

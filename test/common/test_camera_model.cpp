#include <gtest/gtest.h>

#include <array>
#include <string>
#include <vector>

#include <opencv2/calib3d.hpp>

#include "bmp/common/camera_config.hpp"
#include "bmp/common/camera_model.hpp"
#include "shared_data.hpp"

namespace bmp {
namespace {

CameraIntrinsics bonn() {
  const Config c = Config::fromFile(test::sourceDir() + "/config/cameras/bonn.yaml");
  return cameraFromConfig(c.section("camera"));
}

TEST(CameraModel, ProjectBackProjectRoundTrip) {
  const CameraModel cam(bonn());
  const Eigen::Vector3d p(0.3, -0.2, 2.0);
  const Eigen::Vector2d uv = cam.projectPinhole(p);
  EXPECT_LT((cam.backProject(uv, 2.0) - p).norm(), 1e-12);
}

// Our distortion must agree with OpenCV's projectPoints, and undistortion must invert it.
TEST(CameraModel, DistortionMatchesOpenCvAndInverts) {
  const CameraIntrinsics k = bonn();
  const CameraModel cam(k);
  const cv::Matx33d K(k.fx, 0, k.cx, 0, k.fy, k.cy, 0, 0, 1);
  const std::vector<double> dist(k.distortion.begin(), k.distortion.end());
  for (double x = -0.5; x <= 0.5; x += 0.25) {
    for (double y = -0.4; y <= 0.4; y += 0.2) {
      std::vector<cv::Point3d> pts{{x, y, 1.0}};
      std::vector<cv::Point2d> out;
      cv::projectPoints(pts, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), K, dist, out);
      const Eigen::Vector2d uv = cam.project({x, y, 1.0});
      EXPECT_NEAR(uv.x(), out[0].x, 1e-9);
      EXPECT_NEAR(uv.y(), out[0].y, 1e-9);
      const Eigen::Vector2d ideal = cam.projectPinhole({x, y, 1.0});
      EXPECT_LT((cam.undistortPixel(uv) - ideal).norm(), 1e-6);
    }
  }
}

// Strong lenses a wide-angle camera may have: undistortion inverts the distortion to well under a
// thousandth of a pixel over the whole image (the fixed-point iteration used before was 0.03 px off at the
// corners for k1 = -0.2, 0.8 px for k1 = 0.5, and diverged for k1 = 1).
TEST(CameraModel, UndistortionInvertsStrongLensesOverTheWholeImage) {
  for (const std::array<double, 5>& d :
       std::vector<std::array<double, 5>>{{-0.2, 0, 0, 0, 0},
                                          {0.5, 0, 0, 0, 0},
                                          {1.0, 0, 0, 0, 0},
                                          {-0.28, 0.07, 0.001, -0.002, 0},
                                          {0.26, -0.95, -0.005, 0.003, 1.16}}) {
    CameraIntrinsics k;  // 640x480, f 525
    k.distortion = d;
    const CameraModel cam(k);
    EXPECT_EQ(undistortionProblem(k), "") << d[0];
    for (int v = 0; v <= k.height; v += 40) {
      for (int u = 0; u <= k.width; u += 40) {
        const Eigen::Vector2d uv(u, v);
        const Eigen::Vector2d ideal = cam.undistortPixel(uv);
        ASSERT_TRUE(ideal.allFinite()) << d[0] << " at " << u << ", " << v;
        const Eigen::Vector3d ray((ideal.x() - k.cx) / k.fx, (ideal.y() - k.cy) / k.fy, 1.0);
        EXPECT_LT((cam.project(ray) - uv).norm(), 1e-6) << d[0] << " at " << u << ", " << v;
      }
    }
  }
}

// A calibration that folds over inside the image has no ray for the pixels beyond the fold: they undistort
// to NaN (once 1e150), and the camera is refused naming a pixel.
TEST(CameraModel, ALensThatFoldsInsideTheImageIsNamedAndItsOuterPixelsHaveNoRay) {
  CameraIntrinsics k;
  k.distortion = {-0.5, 0, 0, 0, 0};  // r (1 - 0.5 r^2) peaks at r = 0.82, inside the 640x480 image at f 525
  const CameraModel cam(k);
  EXPECT_FALSE(cam.undistortPixel({0, 0}).allFinite());
  EXPECT_TRUE(cam.undistortPixel({k.cx, k.cy}).allFinite());
  EXPECT_NE(undistortionProblem(k).find("cannot be undone at pixel (0, 0) of the 640x480 image"),
            std::string::npos)
      << undistortionProblem(k);
  const std::string yaml =
      "camera: {width: 640, height: 480, fx: 525, fy: 525, cx: 319.5, cy: 239.5, distortion: [-0.5, 0, 0, 0, "
      "0], "
      "depth_scale: 5000}";
  try {
    cameraFromConfig(Config::fromString(yaml, "cam.yaml").section("camera"));
    ADD_FAILURE() << "a folding lens was accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("cam.yaml: key 'camera.distortion'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("cannot be undone at pixel"), std::string::npos) << e.what();
  }
}

// One rule for camera files, frames and keyframes: sides and pixel count, focal lengths that fit the image.
TEST(CameraModel, ImageSizeAndFocalLengthBounds) {
  EXPECT_EQ(imageSizeProblem(640, 480), "");
  EXPECT_EQ(imageSizeProblem(4096, 3072), "");  // Azure Kinect's colour
  EXPECT_NE(imageSizeProblem(0, 480), "");
  EXPECT_NE(imageSizeProblem(8193, 1).find("sides 1 to 8192"), std::string::npos);
  EXPECT_NE(imageSizeProblem(8192, 8192).find("at most 16777216 pixels"), std::string::npos);
  CameraIntrinsics k;  // 640x480
  k.fx = k.fy = 542.8;
  EXPECT_EQ(focalLengthProblem(k), "");
  k.fx = 30.0;  // 169 degrees across
  EXPECT_EQ(focalLengthProblem(k), "");
  for (double bad : {0.0, -1.0, 1e-20, 20.0, 1e6, std::nan("")}) {
    k.fx = bad;
    EXPECT_NE(focalLengthProblem(k), "") << bad;
  }
}

TEST(CameraConfig, RejectsWrongDistortionLength) {
  const Config c = Config::fromString(
      "camera: {width: 640, height: 480, fx: 500, fy: 500, cx: 320, cy: 240, distortion: [0, 0], "
      "depth_scale: 5000}",
      "cam.yaml");
  EXPECT_THROW(cameraFromConfig(c.section("camera")), ConfigError);
}

// An impossible camera is an error naming the file and the key: cx 5000 for a 640-wide image once tracked a
// whole sequence and reported ATE 2 m with exit 0.
TEST(CameraConfig, RejectsImpossibleIntrinsicsNamingFileAndKey) {
  const std::string good =
      "{width: 640, height: 480, fx: 500, fy: 500, cx: 320, cy: 240, "
      "distortion: [0, 0, 0, 0, 0], depth_scale: 5000}";
  EXPECT_NO_THROW(cameraFromConfig(Config::fromString("camera: " + good, "cam.yaml").section("camera")));
  const std::pair<std::string, std::string> bad[] = {{"cx: 320", "cx: 5000"},
                                                     {"cx: 320", "cx: -1"},
                                                     {"cy: 240", "cy: 481"},
                                                     {"fx: 500", "fx: .nan"},
                                                     {"fy: 500", "fy: 0"},
                                                     {"width: 640", "width: 0"},
                                                     // start-up walked its border for minutes, or forever
                                                     {"width: 640", "width: 2147483647"},
                                                     {"height: 480", "height: 8193"},
                                                     {"depth_scale: 5000", "depth_scale: -5"},
                                                     {"distortion: [0, 0", "distortion: [1e300, 0"}};
  for (const auto& [from, to] : bad) {
    std::string yaml = good;
    yaml.replace(yaml.find(from), from.size(), to);
    const std::string key = to.substr(0, to.find(':'));
    try {
      cameraFromConfig(Config::fromString("camera: " + yaml, "cam.yaml").section("camera"));
      ADD_FAILURE() << to << " was accepted";
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find("cam.yaml: key 'camera." + key + "'"), std::string::npos)
          << e.what();
    }
  }
}

}  // namespace
}  // namespace bmp

// The map files read back by the libraries people use: map.pcd by PCL, map.bt by OctoMap, the grid by a
// map_server-style reader written here (yaml-cpp + cv::imread), the PLY header, and the pictures.
#include <gtest/gtest.h>
#include <octomap/OcTree.h>
#include <pcl/io/pcd_io.h>
#include <pcl/point_types.h>
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include <opencv2/imgcodecs.hpp>

#include "mapper/map_files.hpp"
#include "mapper/mapper.hpp"
#include "mapper_test_util.hpp"
#include "shared_data.hpp"

namespace bmp::mapper {
namespace {

namespace fs = std::filesystem;

// map_server's loader, as its documentation states it: p = (255 - v) / 255 unless negate; occupied above
// occupied_thresh, free below free_thresh, else unknown. The image's top row is the map's largest y.
struct MapServerMap {
  double resolution = 0;
  double origin_x = 0, origin_y = 0, yaw = 0;
  cv::Mat image;
  double occupied_thresh = 0, free_thresh = 0;
  bool negate = false;

  static MapServerMap load(const fs::path& yaml) {
    const YAML::Node doc = YAML::LoadFile(yaml.string());
    MapServerMap m;
    m.resolution = doc["resolution"].as<double>();
    m.origin_x = doc["origin"][0].as<double>();
    m.origin_y = doc["origin"][1].as<double>();
    m.yaw = doc["origin"][2].as<double>();
    m.negate = doc["negate"].as<int>() != 0;
    m.occupied_thresh = doc["occupied_thresh"].as<double>();
    m.free_thresh = doc["free_thresh"].as<double>();
    m.image =
        cv::imread((yaml.parent_path() / doc["image"].as<std::string>()).string(), cv::IMREAD_GRAYSCALE);
    return m;
  }
  // 100 occupied, 0 free, -1 unknown at a point of the map's plane.
  int at(double x, double y) const {
    const int col = static_cast<int>(std::floor((x - origin_x) / resolution));
    const int row = image.rows - 1 - static_cast<int>(std::floor((y - origin_y) / resolution));
    if (col < 0 || row < 0 || col >= image.cols || row >= image.rows) return -1;
    const double v = image.at<uchar>(row, col);
    const double p = negate ? v / 255.0 : (255.0 - v) / 255.0;
    return p > occupied_thresh ? 100 : p < free_thresh ? 0 : -1;
  }
};

class MapFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = bmp::test::scratchDir("mapper_files");
    ASSERT_TRUE(mapper.integrate(test::wallKeyframe(0, SE3::Identity(), 3.02)).ok);
    ASSERT_TRUE(mapper.integrate(test::wallKeyframe(1, test::translation(0.3, 0, 0), 3.02)).ok);
    written = writeMapFiles((dir / "map").string(), mapper);
  }
  Mapper mapper{test::testSettings()};
  fs::path dir;
  std::vector<std::string> written;
};

TEST_F(MapFiles, EveryFileIsWrittenAndNoTemporaryIsLeft) {
  EXPECT_EQ(written.size(), 9u);
  for (const auto& entry : fs::directory_iterator(dir / "map"))
    EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos) << entry.path();
  for (const char* png : {"cloud_top.png", "cloud_oblique.png", "occupancy.png"}) {
    const cv::Mat image = cv::imread((dir / "map" / png).string());
    EXPECT_GT(image.cols, 50) << png;
    EXPECT_GT(cv::countNonZero(image.reshape(1) != 40), 1000) << png << ": nothing drawn";
  }
}

TEST_F(MapFiles, PcdLoadsWithPcl) {
  pcl::PointCloud<pcl::PointXYZRGB> cloud;
  ASSERT_EQ(pcl::io::loadPCDFile((dir / "map" / "map.pcd").string(), cloud), 0);
  const PointList& ours = mapper.cloud();
  ASSERT_EQ(cloud.size(), ours.size());
  EXPECT_FLOAT_EQ(cloud[10].x, ours[10].x);
  EXPECT_FLOAT_EQ(cloud[10].z, ours[10].z);
  EXPECT_EQ(cloud[10].r, 200);
  EXPECT_EQ(cloud[10].b, 40);
}

TEST_F(MapFiles, PlyHeaderCountsThePoints) {
  std::ifstream in(dir / "map" / "map.ply", std::ios::binary);
  std::string line, header;
  while (std::getline(in, line) && line != "end_header") header += line + "\n";
  EXPECT_NE(header.find("format binary_little_endian 1.0"), std::string::npos);
  EXPECT_NE(header.find("element vertex " + std::to_string(mapper.cloud().size())), std::string::npos);
  const auto body = fs::file_size(dir / "map" / "map.ply") - static_cast<std::uintmax_t>(in.tellg());
  EXPECT_EQ(body, mapper.cloud().size() * 15);
}

TEST_F(MapFiles, OctreeLoadsWithOctomap) {
  octomap::OcTree tree(0.1);
  ASSERT_TRUE(tree.readBinary((dir / "map" / "map.bt").string()));
  EXPECT_DOUBLE_EQ(tree.getResolution(), 0.05);
  const octomap::OcTreeNode* wall = tree.search(0.0, 0.0, 3.025);
  ASSERT_NE(wall, nullptr);
  EXPECT_TRUE(tree.isNodeOccupied(wall));
  const octomap::OcTreeNode* air = tree.search(0.2, 0.0, 1.5);
  ASSERT_NE(air, nullptr);
  EXPECT_FALSE(tree.isNodeOccupied(air));
}

// The mapper writes the octree itself (OctoMap's own writers print to the process's output): the bytes must
// be what OctoMap's writeBinaryConst gives, and nothing may be printed.
TEST_F(MapFiles, OctreeBytesMatchOctomapsWriterAndNothingIsPrinted) {
  ::testing::internal::CaptureStdout();
  ::testing::internal::CaptureStderr();
  const std::string file = mapper.occupancy().binaryFile();
  const std::string data = mapper.occupancy().binaryData();
  const std::string printed =
      ::testing::internal::GetCapturedStdout() + ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(printed, "");
  std::ostringstream reference_file, reference_data;
  mapper.occupancy().tree().writeBinaryConst(reference_file);
  mapper.occupancy().tree().writeBinaryData(reference_data);
  EXPECT_EQ(file, reference_file.str());
  EXPECT_EQ(data, reference_data.str());
}

TEST_F(MapFiles, GridLoadsAsAMapServerMap) {
  const MapServerMap m = MapServerMap::load(dir / "map" / "occupancy.yaml");
  ASSERT_FALSE(m.image.empty());
  EXPECT_DOUBLE_EQ(m.resolution, 0.05);
  EXPECT_DOUBLE_EQ(m.yaw, 0.0);
  // Up is the camera's -y, so the plane's axes are world x and world z (see occupancy.yaml's comments).
  EXPECT_EQ(m.at(0.0, 3.025), 100);
  EXPECT_EQ(m.at(0.0, 1.5), 0);
  EXPECT_EQ(m.at(0.0, 5.0), -1);
  const OccupancyGrid2D grid = mapper.grid();
  EXPECT_EQ(m.image.cols, grid.width);
  EXPECT_EQ(m.image.rows, grid.height);
  EXPECT_NEAR(m.origin_x, grid.origin.x(), 1e-6);
  EXPECT_NEAR(m.origin_y, grid.origin.y(), 1e-6);
}

std::string readAll(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

TEST_F(MapFiles, TheYamlNamesAnImageNoLaterSaveRewrites) {
  const fs::path map = dir / "map";
  EXPECT_EQ(YAML::LoadFile((map / "occupancy.yaml").string())["image"].as<std::string>(), "occupancy.1.pgm");
  const std::string first_yaml = readAll(map / "occupancy.yaml");
  // The map grows: the next save has another size and origin.
  ASSERT_TRUE(mapper.integrate(test::wallKeyframe(2, test::translation(1.5, 0, 0), 3.02)).ok);
  writeMapFiles(map.string(), mapper);
  // A planner that read the first YAML just before that save still finds the image it names, unchanged.
  const std::string second_image = readAll(map / "occupancy.2.pgm");
  EXPECT_NE(readAll(map / "occupancy.1.pgm"), second_image);
  EXPECT_EQ(readAll(map / "occupancy.pgm"), second_image);
  EXPECT_EQ(YAML::LoadFile((map / "occupancy.yaml").string())["image"].as<std::string>(), "occupancy.2.pgm");
  const MapServerMap m = MapServerMap::load(map / "occupancy.yaml");
  EXPECT_EQ(m.image.cols, mapper.grid().width);
  EXPECT_EQ(m.image.rows, mapper.grid().height);
  // Only the last two saves' images are kept.
  writeMapFiles(map.string(), mapper);
  EXPECT_FALSE(fs::exists(map / "occupancy.1.pgm"));
  EXPECT_TRUE(fs::exists(map / "occupancy.2.pgm"));
  EXPECT_TRUE(fs::exists(map / "occupancy.3.pgm"));
  EXPECT_NE(first_yaml, readAll(map / "occupancy.yaml"));
}

}  // namespace
}  // namespace bmp::mapper

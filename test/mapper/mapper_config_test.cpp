// The mapper's configuration: the shipped file loads whole, defaults hold, every rule names file and key.
#include <gtest/gtest.h>

#include <string>

#include "bmp/common/config.hpp"
#include "mapper/lcm/process_settings.hpp"
#include "mapper/mapper_config.hpp"

namespace bmp::mapper {
namespace {

MapperSettings fromYaml(const std::string& yaml) {
  const Config c = Config::fromString(yaml, "test.yaml");
  MapperSettings s = mapperSettingsFromConfig(c.section("mapper"));
  c.finish();
  return s;
}

// The ConfigError's text, or "" when the YAML is accepted.
std::string errorOf(const std::string& yaml) {
  try {
    fromYaml(yaml);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(MapperConfig, ShippedFileLoadsWithEveryKeyRead) {
  const Config c = Config::fromFile(std::string(BMP_SOURCE_DIR) + "/config/mapper.yaml");
  const MapperSettings s = mapperSettingsFromConfig(c.section("mapper"));
  const MapperProcessSettings p = processSettingsFromConfig(c.section("process"));
  EXPECT_NO_THROW(c.finish());
  EXPECT_DOUBLE_EQ(s.octomap.resolution_m, 0.05);
  EXPECT_DOUBLE_EQ(s.grid.up[1], -1.0);  // the tracker's first camera: y down
  EXPECT_EQ(p.grid_channel, "OCCUPANCY_GRID");
}

TEST(MapperConfig, EmptySectionKeepsDefaults) {
  const MapperSettings s = fromYaml("mapper: {}\n");
  const MapperSettings d;
  EXPECT_EQ(s.cloud.mask_dilation_px, d.cloud.mask_dilation_px);
  EXPECT_DOUBLE_EQ(s.cloud.max_depth_m, d.cloud.max_depth_m);
  EXPECT_DOUBLE_EQ(s.rebuild.min_interval_s, d.rebuild.min_interval_s);
}

TEST(MapperConfig, UpIsNormalised) {
  const MapperSettings s = fromYaml("mapper:\n  grid:\n    up: [0, 0, 2]\n");
  EXPECT_DOUBLE_EQ(s.grid.up[2], 1.0);
}

TEST(MapperConfig, RulesNameFileAndKey) {
  const std::pair<const char*, const char*> cases[] = {
      {"mapper:\n  cloud:\n    min_depth_m: 0\n", "mapper.cloud.min_depth_m"},
      {"mapper:\n  cloud:\n    max_depth_m: 0.2\n", "mapper.cloud.max_depth_m"},
      {"mapper:\n  cloud:\n    mask_dilation_px: -1\n", "mapper.cloud.mask_dilation_px"},
      {"mapper:\n  cloud:\n    pixel_step: 0\n", "mapper.cloud.pixel_step"},
      {"mapper:\n  cloud:\n    map_voxel_m: .nan\n", "mapper.cloud.map_voxel_m"},
      {"mapper:\n  octomap:\n    resolution_m: 0.001\n", "mapper.octomap.resolution_m"},
      {"mapper:\n  octomap:\n    prob_hit: 0.4\n", "mapper.octomap.prob_hit"},
      {"mapper:\n  octomap:\n    prob_miss: 0.6\n", "mapper.octomap.prob_miss"},
      {"mapper:\n  octomap:\n    clamp_max: 0.1\n", "mapper.octomap.clamp_max"},
      {"mapper:\n  rebuild:\n    min_interval_s: -1\n", "mapper.rebuild.min_interval_s"},
      {"mapper:\n  rebuild:\n    min_rotation_deg: 200\n", "mapper.rebuild.min_rotation_deg"},
      {"mapper:\n  grid:\n    up: [0, 0, 0]\n", "mapper.grid.up"},
      {"mapper:\n  grid:\n    floor:\n      mode: guess\n", "mapper.grid.floor.mode"},
      {"mapper:\n  grid:\n    floor:\n      max_tilt_deg: 95\n", "mapper.grid.floor.max_tilt_deg"},
      {"mapper:\n  grid:\n    up: [0, 1]\n", "mapper.grid.up"},
      {"mapper:\n  grid:\n    height_max_m: -2\n", "mapper.grid.height_max_m"},
      {"mapper:\n  grid:\n    resolution_m: 0.02\n", "mapper.grid.resolution_m"},  // finer than the octree
      {"mapper:\n  pictures:\n    size_px: 10\n", "mapper.pictures.size_px"},
      {"mapper:\n  pictures:\n    oblique_elevation_deg: 90\n", "mapper.pictures.oblique_elevation_deg"},
  };
  for (const auto& [yaml, key] : cases) {
    const std::string error = errorOf(yaml);
    EXPECT_NE(error.find("test.yaml"), std::string::npos) << yaml << " -> " << error;
    EXPECT_NE(error.find(key), std::string::npos) << yaml << " -> " << error;
  }
}

TEST(MapperConfig, MisspeltKeyIsRefused) {
  EXPECT_NE(errorOf("mapper:\n  cloud:\n    max_depht_m: 4\n").find("max_depht_m"), std::string::npos);
}

TEST(MapperConfig, ProcessRules) {
  const auto error = [](const std::string& yaml) -> std::string {
    try {
      processSettingsFromConfig(Config::fromString(yaml, "p.yaml").section("process"));
    } catch (const ConfigError& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_NE(error("process:\n  grid_period_s: 0\n").find("process.grid_period_s"), std::string::npos);
  EXPECT_NE(error("process:\n  save_period_s: -1\n").find("process.save_period_s"), std::string::npos);
  EXPECT_NE(error("process:\n  max_cloud_points: 1000000\n").find("max_cloud_points"), std::string::npos);
  EXPECT_NE(error("process:\n  cloud_channel: ''\n").find("process.cloud_channel"), std::string::npos);
  EXPECT_NE(error("process:\n  inbox_mib: 0\n").find("process.inbox_mib"), std::string::npos);
  EXPECT_NE(error("process:\n  inbox_mib: .nan\n").find("process.inbox_mib"), std::string::npos);
  EXPECT_EQ(error("process:\n  save_period_s: 0\n"), "");
}

}  // namespace
}  // namespace bmp::mapper

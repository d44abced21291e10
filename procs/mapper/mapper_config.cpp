#include "mapper/mapper_config.hpp"

#include <cmath>
#include <string>
#include <vector>

namespace bmp::mapper {

namespace {

template <typename T>
void read(const Config& c, const std::string& key, T& value) {
  value = c.get<T>(key, value);
}

void positive(const Config& c, const std::string& key, double value) {
  c.check(std::isfinite(value) && value > 0.0, key, "must be a positive number");
}

void probability(const Config& c, const std::string& key, double value) {
  c.check(value > 0.0 && value < 1.0, key, "must be in (0, 1)");
}

CloudSettings readCloud(const Config& c) {
  CloudSettings s;
  read(c, "min_depth_m", s.min_depth_m);
  read(c, "max_depth_m", s.max_depth_m);
  read(c, "mask_dilation_px", s.mask_dilation_px);
  read(c, "pixel_step", s.pixel_step);
  read(c, "keyframe_voxel_m", s.keyframe_voxel_m);
  read(c, "map_voxel_m", s.map_voxel_m);
  read(c, "viewer_voxel_m", s.viewer_voxel_m);
  read(c, "drop_carved_below", s.drop_carved_below);
  positive(c, "min_depth_m", s.min_depth_m);
  c.check(s.max_depth_m > s.min_depth_m && std::isfinite(s.max_depth_m), "max_depth_m",
          "must exceed min_depth_m");
  c.check(s.mask_dilation_px >= 0 && s.mask_dilation_px <= 100, "mask_dilation_px", "must be in 0..100");
  c.check(s.pixel_step >= 1 && s.pixel_step <= CloudSettings::kMaxPixelStep, "pixel_step",
          "must be in 1.." + std::to_string(CloudSettings::kMaxPixelStep));
  positive(c, "keyframe_voxel_m", s.keyframe_voxel_m);
  positive(c, "map_voxel_m", s.map_voxel_m);
  positive(c, "viewer_voxel_m", s.viewer_voxel_m);
  c.check(s.drop_carved_below >= 0.0 && s.drop_carved_below < 0.5, "drop_carved_below",
          "must be in [0, 0.5) (0: keep every point)");
  return s;
}

OctomapSettings readOctomap(const Config& c) {
  OctomapSettings s;
  read(c, "resolution_m", s.resolution_m);
  read(c, "max_range_m", s.max_range_m);
  read(c, "prob_hit", s.prob_hit);
  read(c, "prob_miss", s.prob_miss);
  read(c, "clamp_min", s.clamp_min);
  read(c, "clamp_max", s.clamp_max);
  read(c, "occupied_threshold", s.occupied_threshold);
  c.check(s.resolution_m >= 0.01 && s.resolution_m <= 1.0, "resolution_m", "must be in [0.01, 1] metres");
  positive(c, "max_range_m", s.max_range_m);
  c.check(s.prob_hit > 0.5 && s.prob_hit < 1.0, "prob_hit", "must be in (0.5, 1)");
  c.check(s.prob_miss > 0.0 && s.prob_miss < 0.5, "prob_miss", "must be in (0, 0.5)");
  probability(c, "clamp_min", s.clamp_min);
  c.check(s.clamp_max > s.clamp_min && s.clamp_max < 1.0, "clamp_max", "must be in (clamp_min, 1)");
  c.check(s.occupied_threshold > s.clamp_min && s.occupied_threshold < s.clamp_max, "occupied_threshold",
          "must lie between clamp_min and clamp_max");
  return s;
}

MergeSettings readMerge(const Config& c) {
  MergeSettings s;
  read(c, "max_translation_m", s.max_translation_m);
  read(c, "max_rotation_deg", s.max_rotation_deg);
  read(c, "max_scans", s.max_scans);
  c.check(std::isfinite(s.max_translation_m) && s.max_translation_m >= 0.0, "max_translation_m",
          "must not be negative");
  c.check(s.max_rotation_deg >= 0.0 && s.max_rotation_deg <= 180.0, "max_rotation_deg", "must be in 0..180");
  c.check(s.max_scans >= 0 && s.max_scans <= 64, "max_scans", "must be in 0..64");
  return s;
}

RebuildSettings readRebuild(const Config& c) {
  RebuildSettings s;
  read(c, "min_interval_s", s.min_interval_s);
  read(c, "min_translation_m", s.min_translation_m);
  read(c, "min_rotation_deg", s.min_rotation_deg);
  c.check(std::isfinite(s.min_interval_s) && s.min_interval_s >= 0.0, "min_interval_s",
          "must not be negative");
  c.check(std::isfinite(s.min_translation_m) && s.min_translation_m >= 0.0, "min_translation_m",
          "must not be negative");
  c.check(s.min_rotation_deg >= 0.0 && s.min_rotation_deg <= 180.0, "min_rotation_deg", "must be in 0..180");
  return s;
}

FloorSettings readFloor(const Config& c) {
  FloorSettings s;
  const std::string mode = c.get<std::string>("mode", s.mode == FloorMode::kFit ? "fit" : "fixed");
  c.check(mode == "fit" || mode == "fixed", "mode", "must be fit or fixed");
  s.mode = mode == "fit" ? FloorMode::kFit : FloorMode::kFixed;
  read(c, "height_m", s.height_m);
  c.check(std::isfinite(s.height_m), "height_m", "must be finite");
  read(c, "max_tilt_deg", s.max_tilt_deg);
  c.check(s.max_tilt_deg > 0 && s.max_tilt_deg < 90, "max_tilt_deg", "must be in (0, 90) degrees");
  read(c, "inlier_m", s.inlier_m);
  positive(c, "inlier_m", s.inlier_m);
  read(c, "min_share", s.min_share);
  c.check(s.min_share > 0 && s.min_share <= 1, "min_share", "must be in (0, 1]");
  read(c, "iterations", s.iterations);
  c.check(s.iterations >= 1, "iterations", "must be at least 1");
  read(c, "max_points", s.max_points);
  c.check(s.max_points >= 100, "max_points", "must be at least 100");
  read(c, "sample_cell_m", s.sample_cell_m);
  c.check(s.sample_cell_m >= 0.05 && s.sample_cell_m <= 10.0, "sample_cell_m", "must be 0.05 to 10 m");
  return s;
}

GridSettings readGrid(const Config& c) {
  GridSettings s;
  s.floor = readFloor(c.section("floor"));
  read(c, "resolution_m", s.resolution_m);
  read(c, "height_min_m", s.height_min_m);
  read(c, "height_max_m", s.height_max_m);
  read(c, "camera_free_radius_m", s.camera_free_radius_m);
  c.check(
      std::isfinite(s.camera_free_radius_m) && s.camera_free_radius_m >= 0.0 && s.camera_free_radius_m <= 2.0,
      "camera_free_radius_m", "must be in [0, 2] metres");
  const std::vector<double> up = c.get<std::vector<double>>("up", {s.up[0], s.up[1], s.up[2]});
  c.check(up.size() == 3, "up", "must be a list of 3 numbers (x, y, z in the world frame)");
  const double norm = std::sqrt(up[0] * up[0] + up[1] * up[1] + up[2] * up[2]);
  c.check(std::isfinite(norm) && norm > 1e-6, "up", "must be a non-zero finite vector");
  for (int i = 0; i < 3; ++i) s.up[i] = up[i] / norm;
  c.check(s.resolution_m >= 0.01 && s.resolution_m <= 1.0, "resolution_m", "must be in [0.01, 1] metres");
  c.check(std::isfinite(s.height_min_m), "height_min_m", "must be finite");
  c.check(std::isfinite(s.height_max_m) && s.height_max_m > s.height_min_m, "height_max_m",
          "must exceed height_min_m");
  return s;
}

PictureSettings readPictures(const Config& c) {
  PictureSettings s;
  read(c, "size_px", s.size_px);
  read(c, "grid_cell_px", s.grid_cell_px);
  read(c, "oblique_elevation_deg", s.oblique_elevation_deg);
  read(c, "oblique_azimuth_deg", s.oblique_azimuth_deg);
  read(c, "cut_above_m", s.cut_above_m);
  c.check(s.size_px >= 64 && s.size_px <= 8192, "size_px", "must be in 64..8192");
  c.check(s.grid_cell_px >= 1 && s.grid_cell_px <= 32, "grid_cell_px", "must be in 1..32");
  c.check(s.oblique_elevation_deg > 0.0 && s.oblique_elevation_deg < 90.0, "oblique_elevation_deg",
          "must be in (0, 90)");
  c.check(std::isfinite(s.oblique_azimuth_deg), "oblique_azimuth_deg", "must be finite");
  c.check(std::isfinite(s.cut_above_m), "cut_above_m", "must be finite");
  return s;
}

}  // namespace

MapperSettings mapperSettingsFromConfig(const Config& section) {
  MapperSettings s;
  s.cloud = readCloud(section.section("cloud"));
  s.octomap = readOctomap(section.section("octomap"));
  s.rebuild = readRebuild(section.section("rebuild"));
  s.merge = readMerge(section.section("merge"));
  s.grid = readGrid(section.section("grid"));
  s.pictures = readPictures(section.section("pictures"));
  read(section, "world_radius_m", s.world_radius_m);
  positive(section, "world_radius_m", s.world_radius_m);
  read(section, "max_keyframes", s.max_keyframes);
  positive(section, "max_keyframes", s.max_keyframes);
  // The octree cannot tell apart what is finer than its leaves, and its rays end where the cloud does.
  section.section("grid").check(s.grid.resolution_m >= s.octomap.resolution_m - 1e-9, "resolution_m",
                                "must not be finer than octomap.resolution_m");
  return s;
}

}  // namespace bmp::mapper

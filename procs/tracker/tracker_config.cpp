#include "tracker/tracker_config.hpp"

#include <sstream>
#include <string>

namespace bmp::tracker {

namespace {

template <typename T>
std::string text(T value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

// Each reader keeps the struct's default when the key is absent, then checks the value it ended with.
void read(const Config& c, const std::string& key, bool& value) {
  value = c.get<bool>(key, value);
}

template <typename T>
void readIn(const Config& c, const std::string& key, T& value, T lo, T hi) {
  value = c.get<T>(key, value);
  c.check(value >= lo && value <= hi, key, "must be in [" + text(lo) + ", " + text(hi) + "]");
}

template <typename T>
void readAtLeast(const Config& c, const std::string& key, T& value, T lo) {
  value = c.get<T>(key, value);
  c.check(value >= lo, key, "must be at least " + text(lo));
}

void readPositive(const Config& c, const std::string& key, double& value) {
  value = c.get<double>(key, value);
  c.check(value > 0.0, key, "must be positive");
}

void readFraction(const Config& c, const std::string& key, double& value) {
  readIn(c, key, value, 0.0, 1.0);
}

void readSize(const Config& c, const std::string& key, std::size_t& value) {
  int v = static_cast<int>(value);
  readAtLeast(c, key, v, 1);
  value = static_cast<std::size_t>(v);
}

constexpr int kMaxHamming = 256;  // bits of an ORB descriptor

OrbOptions orbOptions(const Config& c) {
  OrbOptions o;
  readAtLeast(c, "num_features", o.num_features, 50);
  readIn(c, "num_levels", o.num_levels, 1, 12);
  o.scale_factor = c.get<double>("scale_factor", o.scale_factor);
  c.check(o.scale_factor > 1.0 && o.scale_factor < 2.0, "scale_factor", "must be in (1, 2)");
  readIn(c, "fast_threshold", o.fast_threshold, 1, 255);
  readIn(c, "fast_min_threshold", o.fast_min_threshold, 1, 255);
  c.check(o.fast_min_threshold <= o.fast_threshold, "fast_min_threshold", "must not exceed fast_threshold");
  readAtLeast(c, "cell_size", o.cell_size, 10);
  return o;
}

TrackingOptions trackingOptions(const Config& c) {
  TrackingOptions o;
  readPositive(c, "min_depth_m", o.min_depth_m);
  readPositive(c, "max_depth_m", o.max_depth_m);
  c.check(o.max_depth_m > o.min_depth_m, "max_depth_m", "must exceed min_depth_m");
  readPositive(c, "close_depth_m", o.close_depth_m);
  readPositive(c, "virtual_baseline_m", o.virtual_baseline_m);
  readAtLeast(c, "init_min_keypoints", o.init_min_keypoints, 1);
  readAtLeast(c, "motion_max_scale", o.motion_max_scale, 1.0);
  readAtLeast(c, "motion_search_radius", o.motion_search_radius, 1);
  readAtLeast(c, "local_search_radius", o.local_search_radius, 1);
  readAtLeast(c, "reloc_search_radius", o.reloc_search_radius, 1);
  readIn(c, "match_threshold_high", o.match_threshold_high, 0, kMaxHamming);
  readIn(c, "match_threshold_low", o.match_threshold_low, 0, kMaxHamming);
  c.check(o.match_threshold_low <= o.match_threshold_high, "match_threshold_low",
          "must not exceed match_threshold_high");
  readIn(c, "local_match_ratio", o.local_match_ratio, 0.0, 1.0);
  readIn(c, "match_depth_ratio", o.match_depth_ratio, 0.0, 1.0);
  readIn(c, "descriptor_match_ratio", o.descriptor_match_ratio, 0.0, 1.0);
  read(c, "check_orientation", o.check_orientation);
  readAtLeast(c, "min_matches_motion", o.min_matches_motion, 0);
  readAtLeast(c, "min_inliers_motion", o.min_inliers_motion, 0);
  readAtLeast(c, "min_inliers_local_map", o.min_inliers_local_map, 0);
  readAtLeast(c, "min_inliers_after_reloc", o.min_inliers_after_reloc, 0);
  readAtLeast(c, "max_local_keyframes", o.max_local_keyframes, 1);
  readAtLeast(c, "temporal_points", o.temporal_points, 0);
  readPositive(c, "recheck_gap_s", o.recheck_gap_s);
  readFraction(c, "recheck_inlier_ratio", o.recheck_inlier_ratio);
  return o;
}

MatcherOptions matcherOptions(const Config& c) {
  MatcherOptions o;
  readIn(c, "min_distance_factor", o.min_distance_factor, 0.0, 1.0);
  readAtLeast(c, "max_distance_factor", o.max_distance_factor, 1.0);
  readIn(c, "min_view_cos", o.min_view_cos, -1.0, 1.0);
  readIn(c, "narrow_view_cos", o.narrow_view_cos, -1.0, 1.0);
  c.check(o.min_view_cos <= o.narrow_view_cos, "min_view_cos", "must not exceed narrow_view_cos");
  readAtLeast(c, "wide_window_factor", o.wide_window_factor, 1.0);
  readIn(c, "fuse_max_distance", o.fuse_max_distance, 0, kMaxHamming);
  readPositive(c, "epipolar_chi2", o.epipolar_chi2);
  return o;
}

PoseOptimizerOptions poseOptions(const Config& c) {
  PoseOptimizerOptions o;
  readAtLeast(c, "rounds", o.rounds, 1);
  readAtLeast(c, "iterations_per_round", o.iterations_per_round, 1);
  readPositive(c, "chi2_mono", o.chi2_mono);
  readPositive(c, "chi2_rgbd", o.chi2_rgbd);
  readAtLeast(c, "consensus_iterations", o.consensus_iterations, 0);
  readPositive(c, "consensus_chi2_factor", o.consensus_chi2_factor);
  read(c, "consensus_graded", o.consensus_graded);
  readAtLeast(c, "mature_observations", o.mature_observations, 0);
  readAtLeast(c, "mature_span_s", o.mature_span_s, 0.0);
  readAtLeast(c, "motion_prior_accel", o.motion_prior_accel, 0.0);
  o.motion_prior_velocity_gain = c.get<double>("motion_prior_velocity_gain", o.motion_prior_velocity_gain);
  c.check(o.motion_prior_velocity_gain > 0.0 && o.motion_prior_velocity_gain <= 1.0,
          "motion_prior_velocity_gain", "must be in (0, 1]");
  readAtLeast(c, "motion_prior_accel_lag_s", o.motion_prior_accel_lag_s, 0.0);
  readAtLeast(c, "motion_prior_accel_unmeasured", o.motion_prior_accel_unmeasured, 0.0);
  o.motion_prior_accel_window_s = c.get<double>("motion_prior_accel_window_s", o.motion_prior_accel_window_s);
  c.check(o.motion_prior_accel_window_s > 2.0 * o.motion_prior_accel_lag_s, "motion_prior_accel_window_s",
          "must be longer than twice motion_prior_accel_lag_s");
  o.young_point_weight = c.get<double>("young_point_weight", o.young_point_weight);
  c.check(o.young_point_weight > 0.0 && o.young_point_weight <= 1.0, "young_point_weight",
          "must be in (0, 1]");
  return o;
}

KeyframeOptions keyframeOptions(const Config& c) {
  KeyframeOptions o;
  readAtLeast(c, "max_frames", o.max_frames, 1);
  readAtLeast(c, "min_frames", o.min_frames, 0);
  c.check(o.min_frames <= o.max_frames, "min_frames", "must not exceed max_frames");
  readFraction(c, "ref_ratio", o.ref_ratio);
  readAtLeast(c, "close_tracked_max", o.close_tracked_max, 0);
  readAtLeast(c, "close_untracked_min", o.close_untracked_min, 0);
  readAtLeast(c, "close_min_frames", o.close_min_frames, 1);
  readAtLeast(c, "new_points_min", o.new_points_min, 0);
  readAtLeast(c, "revisit_distance_m", o.revisit_distance_m, 0.0);
  readAtLeast(c, "revisit_angle_deg", o.revisit_angle_deg, 0.0);
  c.check(o.revisit_angle_deg <= 180.0, "revisit_angle_deg", "must be at most 180");
  readAtLeast(c, "revisit_min_inliers", o.revisit_min_inliers, 0);
  readAtLeast(c, "revisit_min_age_s", o.revisit_min_age_s, 0.0);
  readAtLeast(c, "still_distance_m", o.still_distance_m, 0.0);
  readAtLeast(c, "still_angle_deg", o.still_angle_deg, 0.0);
  c.check(o.still_angle_deg <= 180.0, "still_angle_deg", "must be at most 180");
  readAtLeast(c, "still_min_inliers", o.still_min_inliers, 0);
  return o;
}

MappingOptions mappingOptions(const Config& c) {
  MappingOptions o;
  read(c, "threaded", o.threaded);
  readSize(c, "queue_capacity", o.queue_capacity);
  readAtLeast(c, "ba_window", o.ba_window, 1);
  readAtLeast(c, "ba_iterations_first", o.ba_iterations_first, 0);
  readAtLeast(c, "ba_iterations_second", o.ba_iterations_second, 0);
  readAtLeast(c, "covisibility_min_weight", o.covisibility_min_weight, 1);
  readAtLeast(c, "triangulation_neighbors", o.triangulation_neighbors, 0);
  readAtLeast(c, "fuse_neighbors", o.fuse_neighbors, 0);
  readFraction(c, "point_found_ratio", o.point_found_ratio);
  readAtLeast(c, "point_min_observations", o.point_min_observations, 0);
  readFraction(c, "keyframe_redundancy", o.keyframe_redundancy);
  return o;
}

RefineOptions refineOptions(const Config& c) {
  RefineOptions o;
  readAtLeast(c, "after_keyframes", o.after_keyframes, 0);
  readAtLeast(c, "per_frame", o.per_frame, 1);
  readAtLeast(c, "max_pending", o.max_pending, 0);
  readAtLeast(c, "min_inliers", o.min_inliers, 6);
  readAtLeast(c, "smooth_accel", o.smoother.accel_sigma, 0.0);
  readPositive(c, "smooth_max_gap_s", o.smoother.max_gap_s);
  readAtLeast(c, "smooth_accel_lag_s", o.smoother.accel_lag_s, 0.0);
  return o;
}

RelocalizationOptions relocalizationOptions(const Config& c) {
  RelocalizationOptions o;
  readAtLeast(c, "candidates", o.candidates, 1);
  readAtLeast(c, "score_descriptors", o.score_descriptors, 1);
  // PnP needs four correspondences.
  readAtLeast(c, "min_matches", o.min_matches, 4);
  readAtLeast(c, "ransac_iterations", o.ransac_iterations, 1);
  readPositive(c, "ransac_reprojection_px", o.ransac_reprojection_px);
  readAtLeast(c, "min_pnp_inliers", o.min_pnp_inliers, 4);
  return o;
}

}  // namespace

DynamicOptions dynamicOptions(const Config& c) {
  DynamicOptions o;
  const std::string mode = c.get<std::string>("mode", toString(o.mode));
  try {
    o.mode = parseDynamicMode(mode);
  } catch (const std::invalid_argument& e) {
    c.check(false, "mode", e.what());
  }
  readFraction(c, "lambda", o.lambda);
  readFraction(c, "omega", o.omega);
  readFraction(c, "unmatched_prior", o.unmatched_prior);
  readFraction(c, "threshold", o.threshold);
  c.check(o.lambda + o.omega > 1.0, "omega", "with lambda must exceed 1 (else a box says nothing)");
  // A likelihood of 1 makes the other observation's 0: one observation would fix the probability for good,
  // and a late box could not withdraw its stand-in's.
  c.check(o.lambda < 1.0, "lambda", "must be below 1");
  c.check(o.omega < 1.0, "omega", "must be below 1");
  readFraction(c, "medium_held_overlap", o.medium_held_overlap);
  readFraction(c, "medium_moving_keypoints", o.medium_moving_keypoints);
  readAtLeast(c, "medium_min_moved", o.medium_min_moved, 1);
  readIn(c, "refine_core_fraction", o.refine_core_fraction, 0.05, 1.0);
  readPositive(c, "refine_band_m", o.refine_band_m);
  readAtLeast(c, "refine_band_ratio", o.refine_band_ratio, 0.0);
  readPositive(c, "geo_chi2_factor", o.geo_chi2_factor);
  readFraction(c, "geo_lambda", o.geo_lambda);
  readFraction(c, "geo_omega", o.geo_omega);
  c.check(o.geo_lambda + o.geo_omega > 1.0, "geo_omega", "with geo_lambda must exceed 1");
  c.check(o.geo_lambda < 1.0, "geo_lambda", "must be below 1");
  c.check(o.geo_omega < 1.0, "geo_omega", "must be below 1");
  readIn(c, "geo_transition", o.geo_transition, 0.0, 0.5);
  readAtLeast(c, "neighbour_radius_px", o.neighbour_radius_px, 0.0);
  readPositive(c, "neighbour_depth_m", o.neighbour_depth_m);
  readAtLeast(c, "track_radius_px", o.track_radius_px, 0.0);
  readIn(c, "track_max_distance", o.track_max_distance, 0, 256);
  readIn(c, "track_ratio", o.track_ratio, 0.1, 1.0);
  readAtLeast(c, "cluster_link_px", o.cluster_link_px, 0.0);
  readAtLeast(c, "cluster_min_moved", o.cluster_min_moved, 0);
  readAtLeast(c, "mask_keypoint_radius_px", o.mask_keypoint_radius_px, 0);
  readIn(c, "box_keypoint_share", o.box_keypoint_share, 0.0, 1.0);
  readAtLeast(c, "stale_box_max_age_s", o.stale_box_max_age_s, 0.0);
  readFraction(c, "stale_box_motion_iou", o.stale_box_motion_iou);
  readAtLeast(c, "stale_box_growth_px_per_s", o.stale_box_growth_px_per_s, 0.0);
  readAtLeast(c, "held_box_s", o.held_box_s, 0.0);
  readIn(c, "held_box_iou", o.held_box_iou, 0.01, 1.0);
  return o;
}

TrackerConfig trackerConfigFromConfig(const Config& section) {
  TrackerConfig cfg;
  cfg.orb = orbOptions(section.section("orb"));
  cfg.tracking = trackingOptions(section.section("tracking"));
  cfg.matcher = matcherOptions(section.section("matcher"));
  cfg.pose = poseOptions(section.section("pose_optimizer"));
  cfg.keyframes = keyframeOptions(section.section("keyframes"));
  cfg.mapping = mappingOptions(section.section("mapping"));
  cfg.reloc = relocalizationOptions(section.section("relocalization"));
  cfg.refine = refineOptions(section.section("refine"));
  cfg.dynamic = dynamicOptions(section.section("dynamic"));
  return cfg;
}

}  // namespace bmp::tracker

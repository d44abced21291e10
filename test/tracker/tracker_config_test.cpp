// The tracker's configuration: config/tracker.yaml states exactly the struct's defaults, and every section
// refuses a value out of range with a ConfigError naming file and key.
#include <gtest/gtest.h>

#include <iomanip>
#include <map>
#include <set>
#include <sstream>
#include <string>

#include "shared_data.hpp"
#include "tracker/tracker_config.hpp"

namespace bmp::tracker {
namespace {

// Every field by its YAML key under `tracker`, printed exactly (doubles to 17 significant digits).
class FieldPrinter {
 public:
  template <typename T>
  void operator()(const std::string& key, const T& value) {
    std::ostringstream out;
    out << std::setprecision(17) << std::boolalpha << value;
    fields_[key] = out.str();
  }
  const std::map<std::string, std::string>& fields() const { return fields_; }

 private:
  std::map<std::string, std::string> fields_;
};

void printOrbAndTracking(const TrackerConfig& c, FieldPrinter& put) {
  put("orb.num_features", c.orb.num_features);
  put("orb.num_levels", c.orb.num_levels);
  put("orb.scale_factor", c.orb.scale_factor);
  put("orb.fast_threshold", c.orb.fast_threshold);
  put("orb.fast_min_threshold", c.orb.fast_min_threshold);
  put("orb.cell_size", c.orb.cell_size);
  const TrackingOptions& t = c.tracking;
  put("tracking.min_depth_m", t.min_depth_m);
  put("tracking.max_depth_m", t.max_depth_m);
  put("tracking.close_depth_m", t.close_depth_m);
  put("tracking.virtual_baseline_m", t.virtual_baseline_m);
  put("tracking.init_min_keypoints", t.init_min_keypoints);
  put("tracking.motion_max_scale", t.motion_max_scale);
  put("tracking.motion_search_radius", t.motion_search_radius);
  put("tracking.local_search_radius", t.local_search_radius);
  put("tracking.reloc_search_radius", t.reloc_search_radius);
  put("tracking.match_threshold_high", t.match_threshold_high);
  put("tracking.match_threshold_low", t.match_threshold_low);
  put("tracking.local_match_ratio", t.local_match_ratio);
  put("tracking.match_depth_ratio", t.match_depth_ratio);
  put("tracking.descriptor_match_ratio", t.descriptor_match_ratio);
  put("tracking.check_orientation", t.check_orientation);
  put("tracking.min_matches_motion", t.min_matches_motion);
  put("tracking.min_inliers_motion", t.min_inliers_motion);
  put("tracking.min_inliers_local_map", t.min_inliers_local_map);
  put("tracking.min_inliers_after_reloc", t.min_inliers_after_reloc);
  put("tracking.max_local_keyframes", t.max_local_keyframes);
  put("tracking.temporal_points", t.temporal_points);
  put("tracking.recheck_gap_s", t.recheck_gap_s);
  put("tracking.recheck_inlier_ratio", t.recheck_inlier_ratio);
}

void printMatcherAndPose(const TrackerConfig& c, FieldPrinter& put) {
  const MatcherOptions& m = c.matcher;
  put("matcher.min_distance_factor", m.min_distance_factor);
  put("matcher.max_distance_factor", m.max_distance_factor);
  put("matcher.min_view_cos", m.min_view_cos);
  put("matcher.narrow_view_cos", m.narrow_view_cos);
  put("matcher.wide_window_factor", m.wide_window_factor);
  put("matcher.fuse_max_distance", m.fuse_max_distance);
  put("matcher.epipolar_chi2", m.epipolar_chi2);
  const PoseOptimizerOptions& p = c.pose;
  put("pose_optimizer.rounds", p.rounds);
  put("pose_optimizer.iterations_per_round", p.iterations_per_round);
  put("pose_optimizer.chi2_mono", p.chi2_mono);
  put("pose_optimizer.chi2_rgbd", p.chi2_rgbd);
  put("pose_optimizer.consensus_iterations", p.consensus_iterations);
  put("pose_optimizer.consensus_chi2_factor", p.consensus_chi2_factor);
  put("pose_optimizer.consensus_graded", p.consensus_graded);
  put("pose_optimizer.mature_observations", p.mature_observations);
  put("pose_optimizer.mature_span_s", p.mature_span_s);
  put("pose_optimizer.young_point_weight", p.young_point_weight);
  put("pose_optimizer.motion_prior_accel", p.motion_prior_accel);
  put("pose_optimizer.motion_prior_velocity_gain", p.motion_prior_velocity_gain);
  put("pose_optimizer.motion_prior_accel_lag_s", p.motion_prior_accel_lag_s);
  put("pose_optimizer.motion_prior_accel_window_s", p.motion_prior_accel_window_s);
  put("pose_optimizer.motion_prior_accel_unmeasured", p.motion_prior_accel_unmeasured);
}

void printKeyframesMappingReloc(const TrackerConfig& c, FieldPrinter& put) {
  const KeyframeOptions& k = c.keyframes;
  put("keyframes.max_frames", k.max_frames);
  put("keyframes.min_frames", k.min_frames);
  put("keyframes.ref_ratio", k.ref_ratio);
  put("keyframes.close_tracked_max", k.close_tracked_max);
  put("keyframes.close_untracked_min", k.close_untracked_min);
  put("keyframes.close_min_frames", k.close_min_frames);
  put("keyframes.new_points_min", k.new_points_min);
  put("keyframes.revisit_distance_m", k.revisit_distance_m);
  put("keyframes.revisit_angle_deg", k.revisit_angle_deg);
  put("keyframes.revisit_min_inliers", k.revisit_min_inliers);
  put("keyframes.revisit_min_age_s", k.revisit_min_age_s);
  put("keyframes.still_distance_m", k.still_distance_m);
  put("keyframes.still_angle_deg", k.still_angle_deg);
  put("keyframes.still_min_inliers", k.still_min_inliers);
  const MappingOptions& m = c.mapping;
  put("mapping.threaded", m.threaded);
  put("mapping.queue_capacity", m.queue_capacity);
  put("mapping.ba_window", m.ba_window);
  put("mapping.ba_iterations_first", m.ba_iterations_first);
  put("mapping.ba_iterations_second", m.ba_iterations_second);
  put("mapping.covisibility_min_weight", m.covisibility_min_weight);
  put("mapping.triangulation_neighbors", m.triangulation_neighbors);
  put("mapping.fuse_neighbors", m.fuse_neighbors);
  put("mapping.point_found_ratio", m.point_found_ratio);
  put("mapping.point_min_observations", m.point_min_observations);
  put("mapping.keyframe_redundancy", m.keyframe_redundancy);
  const RelocalizationOptions& r = c.reloc;
  put("relocalization.candidates", r.candidates);
  put("relocalization.score_descriptors", r.score_descriptors);
  put("relocalization.min_matches", r.min_matches);
  put("relocalization.ransac_iterations", r.ransac_iterations);
  put("relocalization.ransac_reprojection_px", r.ransac_reprojection_px);
  put("relocalization.min_pnp_inliers", r.min_pnp_inliers);
  const RefineOptions& f = c.refine;
  put("refine.after_keyframes", f.after_keyframes);
  put("refine.per_frame", f.per_frame);
  put("refine.max_pending", f.max_pending);
  put("refine.min_inliers", f.min_inliers);
  put("refine.smooth_accel", f.smoother.accel_sigma);
  put("refine.smooth_max_gap_s", f.smoother.max_gap_s);
  put("refine.smooth_accel_lag_s", f.smoother.accel_lag_s);
}

void printDynamic(const TrackerConfig& c, FieldPrinter& put) {
  const DynamicOptions& d = c.dynamic;
  put("dynamic.mode", std::string(toString(d.mode)));
  put("dynamic.lambda", d.lambda);
  put("dynamic.omega", d.omega);
  put("dynamic.unmatched_prior", d.unmatched_prior);
  put("dynamic.threshold", d.threshold);
  put("dynamic.medium_held_overlap", d.medium_held_overlap);
  put("dynamic.medium_moving_keypoints", d.medium_moving_keypoints);
  put("dynamic.medium_min_moved", d.medium_min_moved);
  put("dynamic.refine_core_fraction", d.refine_core_fraction);
  put("dynamic.refine_band_m", d.refine_band_m);
  put("dynamic.refine_band_ratio", d.refine_band_ratio);
  put("dynamic.geo_chi2_factor", d.geo_chi2_factor);
  put("dynamic.geo_lambda", d.geo_lambda);
  put("dynamic.geo_omega", d.geo_omega);
  put("dynamic.geo_transition", d.geo_transition);
  put("dynamic.neighbour_radius_px", d.neighbour_radius_px);
  put("dynamic.neighbour_depth_m", d.neighbour_depth_m);
  put("dynamic.track_radius_px", d.track_radius_px);
  put("dynamic.track_max_distance", d.track_max_distance);
  put("dynamic.track_ratio", d.track_ratio);
  put("dynamic.cluster_link_px", d.cluster_link_px);
  put("dynamic.cluster_min_moved", d.cluster_min_moved);
  put("dynamic.mask_keypoint_radius_px", d.mask_keypoint_radius_px);
  put("dynamic.box_keypoint_share", d.box_keypoint_share);
  put("dynamic.stale_box_max_age_s", d.stale_box_max_age_s);
  put("dynamic.stale_box_motion_iou", d.stale_box_motion_iou);
  put("dynamic.stale_box_growth_px_per_s", d.stale_box_growth_px_per_s);
  put("dynamic.held_box_s", d.held_box_s);
  put("dynamic.held_box_iou", d.held_box_iou);
}

std::map<std::string, std::string> fieldsOf(const TrackerConfig& c) {
  FieldPrinter put;
  printDynamic(c, put);
  printOrbAndTracking(c, put);
  printMatcherAndPose(c, put);
  printKeyframesMappingReloc(c, put);
  return put.fields();
}

std::string messageOf(const std::string& yaml) {
  try {
    trackerConfigFromConfig(Config::fromString(yaml, "bad.yaml"));
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "(no ConfigError)";
}

TEST(TrackerConfigYaml, RepositoryFileEqualsTheStructDefaults) {
  const Config file = Config::fromFile(test::sourceDir() + "/config/tracker.yaml");
  const TrackerConfig loaded = trackerConfigFromConfig(file.section("tracker"));
  file.ignore("process");  // bmp-tracker's LCM side
  EXPECT_NO_THROW(file.finish());
  const auto expected = fieldsOf(TrackerConfig{});
  const auto actual = fieldsOf(loaded);
  ASSERT_EQ(actual.size(), expected.size());
  for (const auto& [key, value] : expected)
    EXPECT_EQ(actual.at(key), value) << "config/tracker.yaml tracker." << key
                                     << " differs from the default in tracker_options.hpp";
}

// The file names every key the reader knows (none falls back to a default), and the comparison above
// covers every one of them.
TEST(TrackerConfigYaml, RepositoryFileNamesEveryKeyAndTheComparisonCoversThem) {
  const Config file = Config::fromFile(test::sourceDir() + "/config/tracker.yaml");
  trackerConfigFromConfig(file.section("tracker"));
  std::set<std::string> read;
  for (const std::string& line : file.effectiveValues()) {
    EXPECT_EQ(line.find("(default)"), std::string::npos) << "config/tracker.yaml lacks " << line;
    const std::string prefix = "tracker.";
    if (line.compare(0, prefix.size(), prefix) == 0)
      read.insert(line.substr(prefix.size(), line.find(" = ") - prefix.size()));
  }
  std::set<std::string> compared;
  for (const auto& [key, value] : fieldsOf(TrackerConfig{})) compared.insert(key);
  EXPECT_EQ(read, compared);
}

TEST(TrackerConfigYaml, PartialFileKeepsTheOtherDefaults) {
  const TrackerConfig c = trackerConfigFromConfig(
      Config::fromString("orb: {num_features: 500}\nmatcher: {epipolar_chi2: 5.0}\n", "partial.yaml"));
  auto expected = fieldsOf(TrackerConfig{});
  expected["orb.num_features"] = "500";
  expected["matcher.epipolar_chi2"] = "5";
  EXPECT_EQ(fieldsOf(c), expected);
}

TEST(TrackerConfigYaml, EverySectionRefusesAValueOutOfRangeNamingFileAndKey) {
  const std::map<std::string, std::string> bad = {
      {"orb: {num_levels: 0}", "orb.num_levels"},
      {"orb: {scale_factor: 2.5}", "orb.scale_factor"},
      {"tracking: {local_match_ratio: 1.5}", "tracking.local_match_ratio"},
      {"tracking: {match_depth_ratio: -0.1}", "tracking.match_depth_ratio"},
      {"tracking: {motion_search_radius: 0}", "tracking.motion_search_radius"},
      {"tracking: {motion_max_scale: 0.5}", "tracking.motion_max_scale"},
      {"matcher: {fuse_max_distance: 300}", "matcher.fuse_max_distance"},
      {"matcher: {min_view_cos: -2}", "matcher.min_view_cos"},
      {"pose_optimizer: {chi2_rgbd: 0}", "pose_optimizer.chi2_rgbd"},
      {"pose_optimizer: {young_point_weight: 0}", "pose_optimizer.young_point_weight"},
      {"pose_optimizer: {motion_prior_accel: -1}", "pose_optimizer.motion_prior_accel"},
      {"pose_optimizer: {motion_prior_velocity_gain: 0}", "pose_optimizer.motion_prior_velocity_gain"},
      {"pose_optimizer: {motion_prior_accel_lag_s: -0.1}", "pose_optimizer.motion_prior_accel_lag_s"},
      {"pose_optimizer: {motion_prior_accel_window_s: 0.3}", "pose_optimizer.motion_prior_accel_window_s"},
      {"pose_optimizer: {motion_prior_accel_unmeasured: -1}", "pose_optimizer.motion_prior_accel_unmeasured"},
      {"keyframes: {ref_ratio: 1.5}", "keyframes.ref_ratio"},
      {"keyframes: {revisit_angle_deg: 200}", "keyframes.revisit_angle_deg"},
      {"keyframes: {revisit_distance_m: -1}", "keyframes.revisit_distance_m"},
      {"keyframes: {close_min_frames: 0}", "keyframes.close_min_frames"},
      {"mapping: {queue_capacity: 0}", "mapping.queue_capacity"},
      {"mapping: {point_found_ratio: -0.1}", "mapping.point_found_ratio"},
      {"refine: {smooth_accel: -1}", "refine.smooth_accel"},
      {"refine: {smooth_max_gap_s: 0}", "refine.smooth_max_gap_s"},
      {"refine: {smooth_accel_lag_s: -0.1}", "refine.smooth_accel_lag_s"},
      {"relocalization: {ransac_reprojection_px: 0}", "relocalization.ransac_reprojection_px"},
      {"relocalization: {min_matches: 3}", "relocalization.min_matches"},
      {"dynamic: {mode: bayes}", "dynamic.mode"},
      {"dynamic: {lambda: 1.2}", "dynamic.lambda"},
      {"dynamic: {stale_box_motion_iou: 1.5}", "dynamic.stale_box_motion_iou"},
      {"dynamic: {held_box_iou: 0}", "dynamic.held_box_iou"},
      {"dynamic: {held_box_s: -1}", "dynamic.held_box_s"},
      {"dynamic: {lambda: 0.4, omega: 0.5}", "dynamic.omega"},
      {"dynamic: {threshold: -1}", "dynamic.threshold"},
      {"dynamic: {refine_band_m: 0}", "dynamic.refine_band_m"},
      {"dynamic: {geo_lambda: 0.2, geo_omega: 0.3}", "dynamic.geo_omega"},
      {"dynamic: {lambda: 1}", "dynamic.lambda"},  // certainty: one observation would fix it for good
      {"dynamic: {omega: 1}", "dynamic.omega"},
      {"dynamic: {geo_lambda: 1}", "dynamic.geo_lambda"},
      {"dynamic: {geo_omega: 1}", "dynamic.geo_omega"},
  };
  for (const auto& [yaml, key] : bad) {
    const std::string msg = messageOf(yaml);
    EXPECT_NE(msg.find("bad.yaml"), std::string::npos) << yaml << ": " << msg;
    EXPECT_NE(msg.find("'" + key + "'"), std::string::npos) << yaml << ": " << msg;
  }
}

TEST(TrackerConfigYaml, MinAboveMaxIsRefused) {
  const std::map<std::string, std::string> bad = {
      {"orb: {fast_threshold: 10, fast_min_threshold: 12}", "orb.fast_min_threshold"},
      {"tracking: {min_depth_m: 2.0, max_depth_m: 1.0}", "tracking.max_depth_m"},
      {"tracking: {match_threshold_low: 120}", "tracking.match_threshold_low"},
      {"matcher: {min_view_cos: 0.999}", "matcher.min_view_cos"},
      {"keyframes: {min_frames: 40}", "keyframes.min_frames"},
  };
  for (const auto& [yaml, key] : bad) {
    const std::string msg = messageOf(yaml);
    EXPECT_NE(msg.find("'" + key + "'"), std::string::npos) << yaml << ": " << msg;
  }
}

TEST(TrackerConfigYaml, WrongTypeAndMisspeltKeyAreErrors) {
  EXPECT_NE(messageOf("orb: {num_levels: many}").find("orb.num_levels"), std::string::npos);
  const Config typo = Config::fromString("tracking: {max_depht_m: 5.0}\n", "typo.yaml");
  trackerConfigFromConfig(typo);
  EXPECT_THROW(typo.finish(), ConfigError);
}

}  // namespace
}  // namespace bmp::tracker

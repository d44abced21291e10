#include "tracker/tracker_config.hpp"

#include <string>

namespace bmp::tracker {

namespace {

template <typename T>
void read(const Config& c, const std::string& key, T& value) {
  value = c.get<T>(key, value);
}

void readSize(const Config& c, const std::string& key, std::size_t& value) {
  const int v = c.get<int>(key, static_cast<int>(value));
  if (v < 1) throw ConfigError(c.origin() + ": key '" + c.path(key) + "' must be at least 1");
  value = static_cast<std::size_t>(v);
}

}  // namespace

TrackerConfig trackerConfigFromConfig(const Config& section) {
  TrackerConfig cfg;
  const Config orb = section.section("orb");
  read(orb, "num_features", cfg.orb.num_features);
  read(orb, "num_levels", cfg.orb.num_levels);
  read(orb, "scale_factor", cfg.orb.scale_factor);
  read(orb, "fast_threshold", cfg.orb.fast_threshold);
  read(orb, "fast_min_threshold", cfg.orb.fast_min_threshold);
  read(orb, "cell_size", cfg.orb.cell_size);
  orb.check(cfg.orb.num_features >= 50, "num_features", "must be at least 50");
  orb.check(cfg.orb.num_levels >= 1 && cfg.orb.num_levels <= 12, "num_levels", "must be in 1..12");
  orb.check(cfg.orb.scale_factor > 1.0 && cfg.orb.scale_factor < 2.0, "scale_factor", "must be in (1, 2)");
  orb.check(cfg.orb.cell_size >= 10, "cell_size", "must be at least 10");

  const Config t = section.section("tracking");
  auto& tr = cfg.tracking;
  read(t, "min_depth_m", tr.min_depth_m);
  read(t, "max_depth_m", tr.max_depth_m);
  read(t, "close_depth_m", tr.close_depth_m);
  read(t, "virtual_baseline_m", tr.virtual_baseline_m);
  read(t, "init_min_keypoints", tr.init_min_keypoints);
  read(t, "motion_search_radius", tr.motion_search_radius);
  read(t, "local_search_radius", tr.local_search_radius);
  read(t, "reloc_search_radius", tr.reloc_search_radius);
  read(t, "match_threshold_high", tr.match_threshold_high);
  read(t, "match_threshold_low", tr.match_threshold_low);
  read(t, "local_match_ratio", tr.local_match_ratio);
  read(t, "descriptor_match_ratio", tr.descriptor_match_ratio);
  read(t, "check_orientation", tr.check_orientation);
  read(t, "min_matches_motion", tr.min_matches_motion);
  read(t, "min_inliers_motion", tr.min_inliers_motion);
  read(t, "min_inliers_local_map", tr.min_inliers_local_map);
  read(t, "min_inliers_after_reloc", tr.min_inliers_after_reloc);
  read(t, "max_local_keyframes", tr.max_local_keyframes);
  read(t, "temporal_points", tr.temporal_points);
  t.check(tr.min_depth_m > 0 && tr.max_depth_m > tr.min_depth_m, "max_depth_m",
          "must exceed min_depth_m > 0");
  t.check(tr.close_depth_m > 0, "close_depth_m", "must be positive");
  t.check(tr.virtual_baseline_m > 0, "virtual_baseline_m", "must be positive");

  const Config p = section.section("pose_optimizer");
  read(p, "rounds", cfg.pose.rounds);
  read(p, "iterations_per_round", cfg.pose.iterations_per_round);
  read(p, "chi2_mono", cfg.pose.chi2_mono);
  read(p, "chi2_rgbd", cfg.pose.chi2_rgbd);
  read(p, "consensus_iterations", cfg.pose.consensus_iterations);
  read(p, "consensus_chi2_factor", cfg.pose.consensus_chi2_factor);
  read(p, "mature_observations", cfg.pose.mature_observations);
  read(p, "mature_span_s", cfg.pose.mature_span_s);
  read(p, "young_point_weight", cfg.pose.young_point_weight);
  p.check(cfg.pose.young_point_weight > 0.0 && cfg.pose.young_point_weight <= 1.0, "young_point_weight",
          "must be in (0, 1]");
  p.check(cfg.pose.rounds >= 1, "rounds", "must be at least 1");
  p.check(cfg.pose.mature_span_s >= 0.0, "mature_span_s", "must not be negative");
  p.check(cfg.pose.mature_observations >= 0, "mature_observations", "must not be negative");

  const Config k = section.section("keyframes");
  read(k, "max_frames", cfg.keyframes.max_frames);
  read(k, "min_frames", cfg.keyframes.min_frames);
  read(k, "ref_ratio", cfg.keyframes.ref_ratio);
  read(k, "close_tracked_max", cfg.keyframes.close_tracked_max);
  read(k, "close_untracked_min", cfg.keyframes.close_untracked_min);
  read(k, "new_points_min", cfg.keyframes.new_points_min);

  const Config m = section.section("mapping");
  auto& mp = cfg.mapping;
  read(m, "threaded", mp.threaded);
  readSize(m, "queue_capacity", mp.queue_capacity);
  read(m, "ba_window", mp.ba_window);
  read(m, "ba_iterations_first", mp.ba_iterations_first);
  read(m, "ba_iterations_second", mp.ba_iterations_second);
  read(m, "covisibility_min_weight", mp.covisibility_min_weight);
  read(m, "triangulation_neighbors", mp.triangulation_neighbors);
  read(m, "fuse_neighbors", mp.fuse_neighbors);
  read(m, "point_found_ratio", mp.point_found_ratio);
  read(m, "point_min_observations", mp.point_min_observations);
  read(m, "keyframe_redundancy", mp.keyframe_redundancy);
  m.check(mp.ba_window >= 1, "ba_window", "must be at least 1");

  const Config r = section.section("relocalization");
  read(r, "candidates", cfg.reloc.candidates);
  read(r, "score_descriptors", cfg.reloc.score_descriptors);
  read(r, "min_matches", cfg.reloc.min_matches);
  read(r, "ransac_iterations", cfg.reloc.ransac_iterations);
  read(r, "ransac_reprojection_px", cfg.reloc.ransac_reprojection_px);
  read(r, "min_pnp_inliers", cfg.reloc.min_pnp_inliers);
  return cfg;
}

}  // namespace bmp::tracker

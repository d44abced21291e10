#pragma once
// Every tunable of the tracker, with its default. The library never reads files: tracker_config.hpp fills
// this from YAML (config/tracker.yaml), tests set fields directly.
#include <cstddef>
#include <string>

#include "tracker/trajectory_smoother.hpp"

namespace bmp::tracker {

struct OrbOptions {
  int num_features = 1000;     // per frame, over all levels
  int num_levels = 8;          // pyramid levels
  double scale_factor = 1.2;   // between levels
  int fast_threshold = 20;     // FAST threshold a cell uses first
  int fast_min_threshold = 7;  // used in cells where the first finds nothing
  int cell_size = 30;          // pixels of the cells that get the lower threshold
};

struct TrackingOptions {
  double min_depth_m = 0.1;  // keypoint depth outside [min, max] counts as none
  double max_depth_m = 8.0;
  double close_depth_m = 3.0;        // closer: depth is trusted (3-D residual, map point at once)
  double virtual_baseline_m = 0.08;  // turns depth into a right-image coordinate u - fx*b/z
  int init_min_keypoints = 500;      // keypoints with depth needed to start the map
  // The constant-velocity guess is scaled over at most this many frame intervals (beyond, the reference
  // keyframe). Compared without slack: 3 dropped frames make 3.99-4.01 intervals as stamps jitter. 4.5 and
  // 6.5 (every burst of up to 3 or 5 guessed) were no better over Bonn with dropped frames (README).
  double motion_max_scale = 4.0;
  int motion_search_radius = 7;    // pixels at level 0, projection from the last frame
  int local_search_radius = 3;     // pixels at level 0, projection of the local map
  int reloc_search_radius = 5;     // local map radius in the frames just after relocalisation
  int match_threshold_high = 100;  // Hamming distance accepted for projection matches
  int match_threshold_low = 50;    // stricter threshold for descriptor-only matches
  double local_match_ratio = 0.8;  // best / second best (same level) in local map search
  // A keypoint whose depth differs from the projected point's by more than this share of it is not that
  // point: an occluder in front of it (a person before the wall) or what is there since it went (0: off).
  double match_depth_ratio = 0.08;
  double descriptor_match_ratio = 0.75;  // Lowe ratio for keyframe and relocalisation matching
  bool check_orientation = true;         // rotation histogram consistency in frame-to-frame matches
  int min_matches_motion = 20;           // matches needed before optimising the motion-model pose
  int min_inliers_motion = 10;           // inliers after optimisation for the motion model to count
  int min_inliers_local_map = 20;        // inliers after local-map tracking for the frame to be OK
  int min_inliers_after_reloc = 50;      // same, in the frames just after relocalisation
  int max_local_keyframes = 60;          // size cap of the local map
  int temporal_points = 0;               // nearest depth points made temporary in the last frame (0: off)
  // A frame more than recheck_gap_s after the last (frames were dropped) whose motion-model pose keeps under
  // recheck_inlier_ratio of the last frame's tracked points is also tracked from the reference keyframe,
  // and the pose with more inliers kept (ratio 0: off).
  double recheck_gap_s = 0.05;
  double recheck_inlier_ratio = 0.5;
};

// Projection search (matcher.cpp): which map points are worth looking for in a view, and how wide to look.
struct MatcherOptions {
  // A point is looked for between these factors times the distances its descriptor suits
  // (MapPoint::min_distance, max_distance), and only from within this angle of its mean viewing direction.
  double min_distance_factor = 0.8;
  double max_distance_factor = 1.2;
  double min_view_cos = 0.5;
  double narrow_view_cos = 0.998;   // local map: above this cosine the window keeps its radius ...
  double wide_window_factor = 1.6;  // ... below it, it widens by this factor
  int fuse_max_distance = 50;       // Hamming distance accepted when fusing duplicates
  double epipolar_chi2 = 3.84;      // triangulation: squared distance to the epipolar line / sigma^2 (1 dof)
};

struct PoseOptimizerOptions {
  int rounds = 4;  // optimisation rounds with outlier re-classification
  int iterations_per_round = 10;
  double chi2_mono = 5.991;            // 95 % chi-square, 2 dof
  double chi2_rgbd = 7.815;            // 95 % chi-square, 3 dof
  int consensus_iterations = 60;       // 3-point hypotheses tried against the prediction (0: off)
  double consensus_chi2_factor = 1.0;  // inlier test while scoring hypotheses, times chi2
  // Score a hypothesis by how well it explains each match (MSAC), not by how many it explains: the
  // unknown_mover scene's box 2.4 m away otherwise wins against the background (ATE 25 cm, 5 mm graded).
  bool consensus_graded = true;
  int mature_observations = 3;  // keyframes that must see a point before it counts fully
  // ... spread over at least this time (first to last keyframe; 0: any). It keeps movers the detector does
  // not know out of the pose (the default synthetic scene's boxes: 0.8 cm with 1 s, 12.8 cm without).
  // unknown_mover's 275 mm, once blamed on it, came from the consensus counting matches (consensus_graded).
  double mature_span_s = 1.0;
  double young_point_weight = 0.05;  // cost weight of a younger point, pose and local BA (temporary: 0 kfs)
  // A frame's position is held to its constant-velocity prediction, with the spread an unknown acceleration
  // of this size gives (m/s^2; 0: no prior): a / 2 dt^2, 4.5 mm at 30 Hz (motion_prior.hpp says why).
  double motion_prior_accel = 9.0;
  double motion_prior_velocity_gain = 0.3;  // each tracked frame's velocity enters the predicting one so
  // A camera that moves harder than motion_prior_accel has its acceleration measured over this lag (s; 0:
  // motion_prior_accel always) from the frames tracked in the last window, and the spread widened to it;
  // until the window has frames enough to measure, the spread stands for motion_prior_accel_unmeasured.
  double motion_prior_accel_lag_s = 0.2;
  double motion_prior_accel_window_s = 1.5;
  double motion_prior_accel_unmeasured = 18.0;
};

struct KeyframeOptions {
  int max_frames = 30;           // a keyframe at least this often (frames)
  int min_frames = 0;            // and not more often than this
  double ref_ratio = 0.75;       // inliers below this fraction of the reference keyframe's points
  int close_tracked_max = 100;   // fewer tracked close points than this ...
  int close_untracked_min = 70;  // ... while this many close keypoints are unmatched: insert
  // ... but not before this many frames after the last keyframe. A keyframe's new points need a frame or
  // two to be found again; until then their keypoints still look like missing structure. On a mover the
  // detector does not know they never are found again (it moved), so without a wait it called for a
  // keyframe on almost every frame (86 in 300 frames of the synthetic main job; 46 with 3).
  int close_min_frames = 3;
  int new_points_min = 100;  // map points created from depth per keyframe, at least (closest first)
  // A place mapped earlier gets no new keyframe: none while a keyframe of the local map at least
  // revisit_min_age_s old sees from within this distance and angle and the frame still tracks this many
  // inliers. A room revisited for hours then keeps the keyframes it has (bounded memory) instead of adding
  // a new set on every pass; the first pass through a place is not affected.
  double revisit_distance_m = 0.10;
  double revisit_angle_deg = 10.0;
  int revisit_min_inliers = 50;
  double revisit_min_age_s = 10.0;
  // A camera at rest gets no new keyframe: none while the frame is within this distance and angle of its
  // reference keyframe and still tracks this many inliers. From where the last keyframe stands, another adds
  // no baseline, only the movers in front of it; when people cover the view a keyframe was made on nearly
  // every frame, and local BA over near-identical keyframes let the resting camera's pose jump by
  // centimetres. 0 distance: off.
  double still_distance_m = 0.01;
  double still_angle_deg = 0.5;
  int still_min_inliers = 100;
};

struct MappingOptions {
  bool threaded = true;              // local mapping in its own thread; false: inline, deterministic
  std::size_t queue_capacity = 3;    // keyframes waiting for local mapping
  int ba_window = 10;                // covisible keyframes optimised together with the new one
  int ba_iterations_first = 5;       // before outlier removal
  int ba_iterations_second = 10;     // after
  int covisibility_min_weight = 15;  // shared points for a covisibility edge
  int triangulation_neighbors = 10;
  int fuse_neighbors = 10;
  double point_found_ratio = 0.25;   // found / visible below this: culled
  int point_min_observations = 2;    // keyframes; a point two keyframes old seen by fewer: culled
  double keyframe_redundancy = 0.9;  // fraction of points seen by 3 other keyframes: culled
};

// The saved trajectory's second look at each frame (frame_refiner.hpp).
struct RefineOptions {
  int after_keyframes =
      5;              // re-estimate a frame when its reference keyframe is this many keyframes old (0: off)
  int per_frame = 2;  // at most this many per tracked frame: the cost is spread, not paid at a keyframe
  int max_pending = 300;     // frames waiting (about 10 kB each); past this the oldest gets its look at once
  int min_inliers = 30;      // fewer agreeing points: the frame keeps the pose it was tracked with
  SmootherOptions smoother;  // the positions written, smoothed over the camera's motion
};

struct RelocalizationOptions {
  int candidates = 5;           // keyframes tried with PnP
  int score_descriptors = 300;  // frame descriptors used to rank keyframes
  int min_matches = 15;         // descriptor matches for a candidate to be tried
  int ransac_iterations = 200;
  double ransac_reprojection_px = 4.0;
  int min_pnp_inliers = 10;
};

// The dynamic stage (dynamic_stage.hpp): which keypoints are kept out of the pose, new map points and
// local BA because they lie on something that moves. `mode` is the ablation switch, each adding to the
// one before: none (static SLAM), boxes (every keypoint in a moving box, at once), paper (the Bayesian
// moving probability of An et al. 2025), depth (+ each person box cut to the person by depth), geometric
// (+ each matched point's residual against the camera motion as a second observation).
enum class DynamicMode { kNone, kBoxes, kPaper, kDepth, kGeometric };

struct DynamicOptions {
  DynamicMode mode = DynamicMode::kGeometric;
  // Beyond the paper (depth and geometric): boxes are cut to the person.
  bool beyondPaper() const { return mode == DynamicMode::kDepth || mode == DynamicMode::kGeometric; }
  double lambda = 0.9;           // P(z = d | dynamic) of a box observation (the paper's lambda)
  double omega = 0.9;            // P(z = s | static) of a box observation (the paper's omega)
  double unmatched_prior = 0.5;  // prior of a keypoint matched to nothing
  double threshold = 0.5;        // P(dynamic) above this: out of the pose, new points and BA
  // A medium-dynamic box (chair, cup) counts as moving when this share of it lies in a person's box ...
  double medium_held_overlap = 0.5;
  // ... or (geometric) when this share of the last frame's keypoints inside it that were judged moved.
  double medium_moving_keypoints = 0.5;
  // ... and at least this many of them moved: one keypoint's verdict may be a mismatch.
  int medium_min_moved = 3;
  // Depth refinement: the person's depth is the median over the central core_fraction of the box; box
  // pixels within max(band_m, band_ratio * depth) of it are the person's, the rest is background.
  double refine_core_fraction = 0.4;
  double refine_band_m = 0.35;
  double refine_band_ratio = 0.15;
  // Geometric observation: a matched point whose residual under the estimated pose exceeds
  // geo_chi2_factor times the pose's chi-square threshold is observed moving (z = d), else static.
  double geo_chi2_factor = 8.0;
  double geo_lambda = 0.9;   // P(large residual | dynamic)
  double geo_omega = 0.999;  // P(small residual | static)
  // Geometric: P(a point changes between moving and static from one frame to the next). A prior carried
  // from history never sinks below it, so a box that starts moving after seconds at rest is not held
  // static by its past.
  double geo_transition = 0.05;
  // An unmatched keypoint takes its prior from matched neighbours this close (pixels, and metres in
  // depth), so the rest of a mover's keypoints are not each a fresh 0.5.
  double neighbour_radius_px = 24.0;
  double neighbour_depth_m = 0.3;
  // An unmatched keypoint is tracked to the last frame's keypoint with its descriptor (at most
  // track_max_distance, ratio to the second best under track_ratio) within track_radius_px of where that one
  // would be if static (0: off), and takes its posterior as prior (every Bayesian mode, as the paper does);
  // geometric also judges its residual: a mover the detector does not know moves beyond the matcher's
  // windows.
  double track_radius_px = 40.0;
  int track_max_distance = 50;
  double track_ratio = 0.8;
  // Geometric: keypoints that moved, linked within cluster_link_px and neighbour_depth_m, form a cluster;
  // one of at least cluster_min_moved that outnumbers the keypoints that stayed in its box and depth range
  // is a mover, and every other keypoint there is observed moving too (0: off). The keyframe mask links
  // the dynamic keypoints outside person regions the same way and masks each such cluster's box.
  double cluster_link_px = 60.0;
  int cluster_min_moved = 5;
  // Keyframe mask: disk drawn around each dynamic keypoint, and the margin around a cluster's box.
  int mask_keypoint_radius_px = 12;
  // Every variant with boxes: the ORB spread counts the area of the frame's person (high-dynamic) boxes
  // at this share, so the keypoint budget goes mostly to the static scene that holds the pose (1: boxes
  // change nothing, as in the paper's extractor).
  double box_keypoint_share = 0.25;
  // Real time: a frame whose own answer has not come is observed with the newest boxes at most this old
  // (0: such frames are tracked on priors alone), each moved on by the image speed it showed since the
  // answer before (its partner there: same class, intersection over union at least stale_box_motion_iou;
  // 0: not moved) and grown by stale_box_growth_px_per_s times its age on every side.
  double stale_box_max_age_s = 0.5;
  double stale_box_motion_iou = 0.3;
  double stale_box_growth_px_per_s = 0.0;
  // Every variant with boxes: a person (high-dynamic) box found in two answers in a row and missing from
  // the next is added to the frame's boxes for up to held_box_s, moved on at the speed those answers
  // showed, until an answer has it again (same class, intersection over union at least held_box_iou with
  // the held box where it would be by then). 0: only the detector's boxes (the paper).
  double held_box_s = 0.5;
  double held_box_iou = 0.3;
};

struct TrackerConfig {
  OrbOptions orb;
  TrackingOptions tracking;
  MatcherOptions matcher;
  PoseOptimizerOptions pose;
  KeyframeOptions keyframes;
  MappingOptions mapping;
  RelocalizationOptions reloc;
  RefineOptions refine;
  DynamicOptions dynamic;
};

const char* toString(DynamicMode mode);
// Throws std::invalid_argument naming the accepted names.
DynamicMode parseDynamicMode(const std::string& name);

}  // namespace bmp::tracker

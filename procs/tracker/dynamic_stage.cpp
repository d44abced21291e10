#include "tracker/dynamic_stage.hpp"

#include <algorithm>
#include <limits>

#include <opencv2/imgproc.hpp>

#include "tracker/key_frame.hpp"
#include "tracker/keypoint_tracks.hpp"
#include "tracker/map_point.hpp"
#include "tracker/moving_clusters.hpp"
#include "tracker/pose_optimizer.hpp"

namespace bmp::tracker {

namespace {

// Probabilities stay inside (floor, 1 - floor): at exactly 0 or 1 Bayes can never move them again.
constexpr double kProbabilityFloor = 1e-3;

bool inside(const cv::Rect2f& r, const cv::Point2f& p) {
  return p.x >= r.x && p.y >= r.y && p.x < r.x + r.width && p.y < r.y + r.height;
}

bool usableMatch(const std::shared_ptr<MapPoint>& mp) {
  return mp && !mp->bad && !mp->temporary();
}

}  // namespace

DynamicStage::DynamicStage(const DynamicOptions& options, const PoseOptimizerOptions& pose)
    : options_(options), pose_(pose) {
  bayes_.lambda = options.lambda;
  bayes_.omega = options.omega;
  bayes_.unmatched_prior = options.unmatched_prior;
  bayes_.threshold = options.threshold;
  geometric_ = bayes_;
  geometric_.lambda = options_.geo_lambda;
  geometric_.omega = options_.geo_omega;
}

double DynamicStage::carried(double p) const {
  if (options_.mode != DynamicMode::kGeometric) return p;
  const double e = options_.geo_transition;
  return p * (1.0 - e) + (1.0 - p) * e;
}

float DynamicStage::clampProbability(double p) const {
  return static_cast<float>(std::clamp(p, kProbabilityFloor, 1.0 - kProbabilityFloor));
}

std::vector<DynamicStage::MovingRegion> DynamicStage::movingRegions(
    const Features& f, const std::vector<ObjectBox>& boxes, const std::vector<float>& moving_share) const {
  RegionOptions ro;
  ro.medium_held_overlap = static_cast<float>(options_.medium_held_overlap);
  ro.medium_moving_keypoints = static_cast<float>(options_.medium_moving_keypoints);
  const std::vector<uint8_t> moving = movingBoxes(boxes, ro, moving_share);
  const bool refine = options_.beyondPaper();
  std::vector<MovingRegion> regions;
  for (std::size_t b = 0; b < boxes.size(); ++b) {
    if (!moving[b]) continue;
    MovingRegion r{boxes[b].box};
    if (refine) {
      // The mover fills the middle of its box; the background shows at the sides and between the legs.
      const float c = static_cast<float>(options_.refine_core_fraction);
      const cv::Rect2f core(r.box.x + r.box.width * (1 - c) / 2, r.box.y + r.box.height * (1 - c) / 2,
                            r.box.width * c, r.box.height * c);
      std::vector<float> depths;
      for (int k = 0; k < f.size(); ++k)
        if (f.depth[k] > 0 && inside(core, f.keys[k].pt)) depths.push_back(f.depth[k]);
      if (depths.size() >= 3) {
        std::nth_element(depths.begin(), depths.begin() + depths.size() / 2, depths.end());
        const float d = depths[depths.size() / 2];
        const float band =
            static_cast<float>(std::max(options_.refine_band_m, options_.refine_band_ratio * d));
        r.near_m = d - band;
        r.far_m = d + band;
      }
    }
    regions.push_back(r);
  }
  return regions;
}

std::vector<int8_t> DynamicStage::boxObservation(const Features& f, const std::vector<ObjectBox>& boxes,
                                                 const std::vector<float>& moving_share) const {
  return regionObservation(f, boxes, movingRegions(f, boxes, moving_share));
}

std::vector<int8_t> DynamicStage::regionObservation(const Features& f, const std::vector<ObjectBox>& boxes,
                                                    const std::vector<MovingRegion>& regions) {
  std::vector<int8_t> z(static_cast<std::size_t>(f.size()), 0);
  for (int k = 0; k < f.size(); ++k) {
    const cv::Point2f& p = f.keys[k].pt;
    bool in_low = false;
    for (const auto& b : boxes) in_low = in_low || (b.level == DynamicLevel::kLow && inside(b.box, p));
    for (const auto& r : regions) {
      // At the mover's depth a keypoint is the mover's even in a low box (a person in front of a TV); without
      // a depth, a low box vetoes as in the paper, and otherwise the keypoint counts as the mover's (the
      // conservative side).
      const bool has_depth = r.far_m > 0 && f.depth[k] > 0;
      const bool at_mover = has_depth && f.depth[k] >= r.near_m && f.depth[k] <= r.far_m;
      if (inside(r.box, p) && (at_mover || (!has_depth && !in_low))) {
        z[k] = 1;
        break;
      }
    }
  }
  return z;
}

void DynamicStage::observe(Frame& frame, const std::vector<ObjectBox>* boxes, const Frame* last) const {
  if (!enabled() || !boxes) return;
  std::vector<float> share;
  // The keypoints' own evidence, not their posterior: that carries this box's earlier observations, so a
  // chair once counted as moving would keep itself moving.
  if (last && last->features)
    share = movedShareInBoxes(last->features->keys, *boxes, last->moved, options_.medium_min_moved);
  frame.box_z = boxObservation(*frame.features, *boxes, share);
  frame.box_moving_share = std::move(share);
  if (options_.mode != DynamicMode::kBoxes) return;
  // Boxes only: a keypoint in a moving box is dynamic in this frame, with no memory.
  for (std::size_t i = 0; i < frame.box_z.size(); ++i) {
    frame.moving[i] = frame.box_z[i];
    frame.dynamic[i] = frame.box_z[i];
  }
}

KeypointWindowGrid DynamicStage::matchedNeighbours(const Frame& frame, const FrameGeometry& g) const {
  // The keypoints a neighbour prior may come from: those in the frame's grid (not excluded) with a usable
  // match and depth. Packed once per frame, an unmatched keypoint's search reads no other keypoint.
  const Features& f = *frame.features;
  const double r = options_.neighbour_radius_px;
  return KeypointWindowGrid::ofFrameGrid(
      f, g, r, [&](int j) { return r > 0 && usableMatch(frame.points[j]) && f.depth[j] > 0; });
}

float DynamicStage::neighbourPrior(const Frame& frame, const KeypointWindowGrid& matched, int i) const {
  const Features& f = *frame.features;
  if (options_.neighbour_radius_px <= 0 || f.depth[i] <= 0)
    return static_cast<float>(options_.unmatched_prior);
  // Exact in any order: every probability is a float in [kProbabilityFloor, 1] (a multiple of 2^-33), and a
  // double holds the sum of up to about 2^20 of them without rounding.
  double sum = 0.0;
  int n = 0;
  matched.forEach(f.un[i].x(), f.un[i].y(), options_.neighbour_radius_px, -1, -1, [&](int j) {
    if (std::abs(f.depth[j] - f.depth[i]) > options_.neighbour_depth_m) return;
    sum += frame.points[j]->moving_probability;
    ++n;
  });
  return n > 0 ? static_cast<float>(sum / n) : static_cast<float>(options_.unmatched_prior);
}

void DynamicStage::applyPriors(Frame& frame) const {
  if (!enabled() || options_.mode == DynamicMode::kBoxes) return;
  for (int i = 0; i < frame.features->size(); ++i) {
    const auto& mp = frame.points[i];
    // An unmatched keypoint takes no part in the pose: its neighbours' prior waits for conclude().
    observeBoxes(frame, i, usableMatch(mp) ? mp->moving_probability : options_.unmatched_prior);
  }
}

void DynamicStage::observeBoxes(Frame& frame, int i, double posterior_before) const {
  const double prior = carried(posterior_before);
  const double p = frame.box_z.empty() ? prior : updateMovingProbability(prior, frame.box_z[i] != 0, bayes_);
  frame.moving[i] = clampProbability(p);
  frame.dynamic[i] = isDynamic(frame.moving[i], bayes_);
}

bool DynamicStage::movedAgainstPose(const Frame& frame, const FrameGeometry& g, int i,
                                    const Eigen::Vector3d& p_world) const {
  const Features& f = *frame.features;
  const PoseCamera camera{g.fx, g.fy, g.cx, g.cy, g.bf};
  const PoseObservation o{p_world, f.un[i], f.uRight(g, i), g.pyramid.inv_sigma2[f.level(i)], 1.0, false};
  const double limit = options_.geo_chi2_factor * (o.u_right >= 0 ? pose_.chi2_rgbd : pose_.chi2_mono);
  return poseChi2(frame.T_cam_world(), o, camera) > limit;
}

void DynamicStage::conclude(Frame& frame, const FrameGeometry& g, const Frame* last) const {
  if (!enabled() || options_.mode == DynamicMode::kBoxes) return;
  const Features& f = *frame.features;
  if (options_.mode == DynamicMode::kGeometric) {
    // Each keypoint's verdict: -1 none, 0 where it should be, 1 moved.
    std::vector<int8_t> verdict(static_cast<std::size_t>(f.size()), -1);
    const KeypointWindowGrid matched = matchedNeighbours(frame, g);
    for (int i = 0; i < f.size(); ++i) {
      const auto& mp = frame.points[i];
      if (!usableMatch(mp)) {
        observeBoxes(frame, i, neighbourPrior(frame, matched, i));
        continue;
      }
      // The residual against the camera motion estimated without the dynamic keypoints.
      verdict[i] = movedAgainstPose(frame, g, i, mp->p_world);
      observeGeometry(frame, i, verdict[i] != 0);
    }
    if (last && last->features && options_.track_radius_px > 0) observeTracks(frame, g, *last, verdict);
    if (options_.cluster_min_moved > 0) observeMovingClusters(frame, g, verdict);
    frame.moved = std::move(verdict);
  } else if (last && last->features && options_.track_radius_px > 0) {
    // The paper's prior for a keypoint matched to no map point: the posterior of its last-frame keypoint.
    const std::vector<int> track = tracksToLast(frame, g, *last);
    for (int i = 0; i < f.size(); ++i)
      if (track[i] >= 0) {
        takeTrackPrior(frame, i, last->moving[track[i]]);
        frame.dynamic[i] = isDynamic(frame.moving[i], bayes_);
      }
  }
}

void DynamicStage::commit(const Frame& frame) const {
  if (!enabled() || options_.mode == DynamicMode::kBoxes) return;
  for (int i = 0; i < frame.features->size(); ++i)
    if (usableMatch(frame.points[i])) frame.points[i]->moving_probability = frame.moving[i];
}

void DynamicStage::observeGeometry(Frame& frame, int i, bool moved) const {
  // Inside a moving region (a person's box, cut to the person by depth) only a large residual counts: a
  // small one says the point is still now, not that it is not on a person, and people stand still. Counted,
  // it wore a standing person's probability down below the threshold within a second or two.
  if (!moved && !frame.box_z.empty() && frame.box_z[i] != 0) return;
  frame.moving[i] = clampProbability(updateMovingProbability(frame.moving[i], moved, geometric_));
  frame.dynamic[i] = isDynamic(frame.moving[i], bayes_);
}

std::vector<int> DynamicStage::tracksToLast(const Frame& frame, const FrameGeometry& g,
                                            const Frame& last) const {
  const Features& f = *frame.features;
  std::vector<uint8_t> open(static_cast<std::size_t>(f.size()), 0);
  for (int i = 0; i < f.size(); ++i) open[i] = !usableMatch(frame.points[i]) && !f.excluded[i];
  KeypointTrackOptions to;
  to.radius_px = options_.track_radius_px;
  to.max_distance = options_.track_max_distance;
  to.ratio = options_.track_ratio;
  return trackFromLastFrame(frame, last, g, open, to);
}

void DynamicStage::takeTrackPrior(Frame& frame, int i, double last_posterior) const {
  const double prior = carried(last_posterior);
  frame.moving[i] = clampProbability(
      frame.box_z.empty() ? prior : updateMovingProbability(prior, frame.box_z[i] != 0, bayes_));
}

void DynamicStage::observeTracks(Frame& frame, const FrameGeometry& g, const Frame& last,
                                 std::vector<int8_t>& verdict) const {
  const Features& f = *frame.features;
  const Features& lf = *last.features;
  const std::vector<int> track = tracksToLast(frame, g, last);
  for (int i = 0; i < f.size(); ++i) {
    const int j = track[i];
    if (j < 0) continue;
    // The last frame's keypoint is the prior (the paper's), updated by this frame's boxes. The verdict is
    // left to observeGeometry: inside a moving region, for a keypoint that stayed, it keeps the one from
    // the neighbours' prior. Recomputed here from the track's prior instead, it let more people's keypoints
    // into new map points: synthetic crowd seeds 1-3 ATE 3.2 / 4.0 / 5.3 -> 4.2 / 4.3 / 6.1 mm, recall
    // within 0.3 points either way (2026-12-06).
    takeTrackPrior(frame, i, last.moving[j]);
    // Judged against where the track began: a slow mover's steps add up.
    const auto& last_mp = last.points[j];
    if (last.anchored[j])
      frame.anchor[i] = last.anchor[j];
    else if (usableMatch(last_mp))
      frame.anchor[i] = last_mp->p_world;
    else
      frame.anchor[i] = last.T_world_cam() * g.camera.backProject(lf.un[j], lf.depth[j]);
    frame.anchored[i] = 1;
    verdict[i] = movedAgainstPose(frame, g, i, frame.anchor[i]);
    observeGeometry(frame, i, verdict[i] != 0);
  }
}

void DynamicStage::observeMovingClusters(Frame& frame, const FrameGeometry& g,
                                         const std::vector<int8_t>& verdict) const {
  // Each keypoint a cluster covers is observed moving, once, unless its own residual already said so: its
  // own "stayed" is the weaker word, most often from a track or a map point only a frame or two old.
  const Features& f = *frame.features;
  const std::vector<MovingCluster> clusters = movingClusters(
      f, g, verdict, options_.cluster_link_px, options_.neighbour_depth_m, options_.cluster_min_moved);
  if (clusters.empty()) return;
  for (int i = 0; i < f.size(); ++i) {
    if (verdict[i] == 1 || f.depth[i] <= 0) continue;
    for (const MovingCluster& c : clusters)
      if (c.covers(f.un[i].x(), f.un[i].y(), f.depth[i], options_.neighbour_depth_m)) {
        observeGeometry(frame, i, true);
        break;
      }
  }
}

std::vector<float> DynamicStage::lateMovingShare(const KeyFrame& kf,
                                                 const std::vector<ObjectBox>& boxes) const {
  // The keyframe's own verdicts are the evidence that a chair moves (the frame after it would have taken
  // them): without them a late answer would undo what its stand-in boxes' observation had counted.
  if (kf.moved.size() != kf.features->keys.size()) return {};
  return movedShareInBoxes(kf.features->keys, boxes, kf.moved, options_.medium_min_moved);
}

void DynamicStage::observeLate(KeyFrame& kf, const std::vector<ObjectBox>& boxes) const {
  if (!enabled() || options_.mode == DynamicMode::kBoxes) return;
  const std::vector<int8_t> z = boxObservation(*kf.features, boxes, lateMovingShare(kf, boxes));
  // Observed with stand-in boxes, the frame's probabilities hold their observation: the frame's own
  // answer takes its place (withdrawn, then applied), so the frame counts once.
  const bool replace = kf.stand_in_z.size() == z.size();
  const auto observe = [&](double p, std::size_t i) {
    if (replace) p = withdrawObservation(p, kf.stand_in_z[i] != 0, bayes_);
    return clampProbability(updateMovingProbability(p, z[i] != 0, bayes_));
  };
  for (std::size_t i = 0; i < z.size(); ++i) {
    kf.moving[i] = observe(kf.moving[i], i);
    kf.dynamic[i] = isDynamic(kf.moving[i], bayes_);
    const auto& mp = kf.points[i];
    if (usableMatch(mp)) mp->moving_probability = observe(mp->moving_probability, i);
  }
  kf.stand_in_z.clear();
}

namespace {

// Marks the pixels of box (clipped to m) with no depth or a depth in [near_m, far_m].
void markAtDepth(const cv::Rect& box, double near_m, double far_m, const cv::Mat& depth, double depth_scale,
                 cv::Mat& m) {
  const cv::Rect r = box & cv::Rect(0, 0, m.cols, m.rows);
  for (int v = r.y; v < r.y + r.height; ++v)
    for (int u = r.x; u < r.x + r.width; ++u) {
      const double d = depthMetresAt(depth, u, v, depth_scale);
      if (d <= 0 || (d >= near_m && d <= far_m)) m.at<uint8_t>(v, u) = 255;
    }
}

}  // namespace

cv::Mat DynamicStage::mask(const Features& f, const FrameGeometry& g, const std::vector<uint8_t>& dynamic,
                           const std::vector<ObjectBox>* boxes, const std::vector<float>& moving_share,
                           const cv::Mat& depth, double depth_scale) const {
  cv::Mat m = cv::Mat::zeros(depth.size(), CV_8UC1);
  if (!enabled()) return m;
  const std::vector<MovingRegion> regions =
      boxes ? movingRegions(f, *boxes, moving_share) : std::vector<MovingRegion>{};
  const cv::Rect image(0, 0, m.cols, m.rows);
  for (const MovingRegion& r : regions) {
    if (r.far_m <= 0)
      m(cv::Rect(r.box) & image).setTo(255);
    else
      markAtDepth(cv::Rect(r.box), r.near_m, r.far_m, depth, depth_scale, m);
  }
  if (options_.mode == DynamicMode::kGeometric && options_.cluster_min_moved > 0) {
    // The movers no box holds: a person's region covers the person already, and a cluster's box spanning
    // several people would take the floor and wall between them.
    std::vector<uint8_t> unboxed = dynamic;
    if (boxes) {
      const std::vector<int8_t> z = regionObservation(f, *boxes, regions);
      for (std::size_t i = 0; i < unboxed.size(); ++i) unboxed[i] = unboxed[i] && !z[i];
    }
    maskDynamicClusters(f, g, unboxed, depth, depth_scale, m);
  }
  for (int i = 0; i < f.size(); ++i)
    if (dynamic[i]) cv::circle(m, f.keys[i].pt, options_.mask_keypoint_radius_px, 255, cv::FILLED);
  return m;
}

void DynamicStage::maskDynamicClusters(const Features& f, const FrameGeometry& g,
                                       const std::vector<uint8_t>& dynamic, const cv::Mat& depth,
                                       double depth_scale, cv::Mat& m) const {
  // The clusters the geometric observation links moved keypoints into, here of the dynamic ones; no
  // keypoint vetoes (those not yet judged dynamic on a mover are what the region is for).
  std::vector<int8_t> verdict(dynamic.size(), -1);
  for (std::size_t i = 0; i < dynamic.size(); ++i)
    if (dynamic[i]) verdict[i] = 1;
  const std::vector<MovingCluster> clusters = movingClusters(
      f, g, verdict, options_.cluster_link_px, options_.neighbour_depth_m, options_.cluster_min_moved);
  const int grow = options_.mask_keypoint_radius_px;
  for (const MovingCluster& c : clusters) {
    // Its box in the (distorted) image the mask is drawn on: of its own keypoints' positions there.
    float u0 = std::numeric_limits<float>::max(), v0 = u0, u1 = -u0, v1 = -u0;
    for (int i = 0; i < f.size(); ++i) {
      if (verdict[i] != 1 || f.depth[i] <= 0 || !c.covers(f.un[i].x(), f.un[i].y(), f.depth[i], 0.0))
        continue;
      const cv::Point2f& p = f.keys[i].pt;
      u0 = std::min(u0, p.x), u1 = std::max(u1, p.x), v0 = std::min(v0, p.y), v1 = std::max(v1, p.y);
    }
    if (u1 < u0) continue;
    const cv::Rect grown(cv::Point(cvFloor(u0) - grow, cvFloor(v0) - grow),
                         cv::Point(cvCeil(u1) + grow + 1, cvCeil(v1) + grow + 1));
    markAtDepth(grown, c.near_m - options_.neighbour_depth_m, c.far_m + options_.neighbour_depth_m, depth,
                depth_scale, m);
  }
}

}  // namespace bmp::tracker

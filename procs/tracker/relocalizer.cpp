#include "tracker/relocalizer.hpp"

#include <algorithm>
#include <unordered_set>

#include <opencv2/calib3d.hpp>

#include "tracker/frame_pose.hpp"
#include "tracker/matcher.hpp"

namespace bmp::tracker {

namespace {

std::vector<std::shared_ptr<MapPoint>> goodPoints(const KeyFrame& kf) {
  std::vector<std::shared_ptr<MapPoint>> out;
  for (const auto& mp : kf.points)
    if (mp && !mp->bad) out.push_back(mp);
  return out;
}

// How many sampled frame descriptors have a point in kf within max_distance.
int similarity(const Features& f, const std::vector<int>& sample, const KeyFrame& kf, int max_distance) {
  std::vector<const uint8_t*> descs;
  for (const auto& mp : kf.points)
    if (mp && !mp->bad) descs.push_back(mp->descriptor.ptr<uint8_t>(0));
  int score = 0;
  for (int i : sample) {
    for (const uint8_t* d : descs) {
      if (hamming(f.descriptor(i), d) <= max_distance) {
        ++score;
        break;
      }
    }
  }
  return score;
}

}  // namespace

std::shared_ptr<KeyFrame> relocalize(Frame& frame, const Map& map, const FrameGeometry& g,
                                     const TrackerConfig& config, const DynamicStage& dynamic) {
  const Features& f = *frame.features;
  const auto& rc = config.reloc;
  const auto& tc = config.tracking;
  std::vector<int> sample;
  std::vector<int> usable;
  for (int i = 0; i < f.size(); ++i)
    if (!f.excluded[i]) usable.push_back(i);
  if (usable.size() < 20) return nullptr;
  const double stride = std::max(1.0, static_cast<double>(usable.size()) / rc.score_descriptors);
  for (double k = 0; k < usable.size(); k += stride) sample.push_back(usable[static_cast<std::size_t>(k)]);

  std::vector<std::pair<int, std::shared_ptr<KeyFrame>>> ranked;
  for (const auto& kf : map.keyFrames())
    if (!kf->bad) ranked.emplace_back(similarity(f, sample, *kf, tc.match_threshold_low), kf);
  std::stable_sort(ranked.begin(), ranked.end(),
                   [](const auto& a, const auto& b) { return a.first > b.first; });
  if (static_cast<int>(ranked.size()) > rc.candidates) ranked.resize(rc.candidates);

  const cv::Matx33d K(g.fx, 0, g.cx, 0, g.fy, g.cy, 0, 0, 1);
  for (const auto& [score, kf] : ranked) {
    if (score < rc.min_matches / 2) break;
    frame.clearMatches();
    std::vector<std::shared_ptr<MapPoint>> matches(f.size());
    if (matchByDescriptors(f, goodPoints(*kf), tc.descriptor_match_ratio, tc.match_threshold_high, matches) <
        rc.min_matches)
      continue;
    std::vector<cv::Point3f> object;
    std::vector<cv::Point2f> image;
    std::vector<int> index;
    for (int i = 0; i < f.size(); ++i) {
      if (!matches[i]) continue;
      const auto& p = matches[i]->p_world;
      object.emplace_back(static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z()));
      image.emplace_back(static_cast<float>(f.un[i].x()), static_cast<float>(f.un[i].y()));
      index.push_back(i);
    }
    cv::Vec3d rvec, tvec;
    std::vector<int> inliers;
    const bool solved =
        cv::solvePnPRansac(object, image, K, cv::noArray(), rvec, tvec, false, rc.ransac_iterations,
                           static_cast<float>(rc.ransac_reprojection_px), 0.99, inliers, cv::SOLVEPNP_AP3P);
    if (!solved || static_cast<int>(inliers.size()) < rc.min_pnp_inliers) continue;
    cv::Matx33d R;
    cv::Rodrigues(rvec, R);
    SE3 T_cam_world = SE3::Identity();
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) T_cam_world.linear()(r, c) = R(r, c);
      T_cam_world.translation()[r] = tvec[r];
    }
    frame.setPose(normalized(T_cam_world).inverse());
    for (int k : inliers) frame.points[index[k]] = matches[index[k]];
    dynamic.applyPriors(frame);
    if (optimizeFramePose(frame, g, config.pose) < rc.min_pnp_inliers) continue;
    dropOutliers(frame);
    // Grow the matches with the keyframe's neighbourhood, then refine again.
    std::vector<std::shared_ptr<MapPoint>> local;
    std::unordered_set<const MapPoint*> seen;
    std::vector<KeyFrame*> around = kf->bestCovisibles(10);
    around.push_back(kf.get());
    for (KeyFrame* k : around)
      for (const auto& mp : k->points)
        if (mp && !mp->bad && seen.insert(mp.get()).second) local.push_back(mp);
    matchLocalPoints(frame, local, g, tc, config.matcher, tc.reloc_search_radius * 2.0);
    dynamic.applyPriors(frame);
    const int good = optimizeFramePose(frame, g, config.pose);
    if (good >= tc.min_inliers_after_reloc) {
      dropOutliers(frame);
      return kf;
    }
  }
  frame.clearMatches();
  return nullptr;
}

}  // namespace bmp::tracker

// LocalMapper's bundle adjustment and triangulation (split from local_mapper.cpp to keep files short).
#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "tracker/frame_pose.hpp"
#include "tracker/local_ba.hpp"
#include "tracker/local_mapper.hpp"
#include "tracker/matcher.hpp"

namespace bmp::tracker {

void LocalMapper::bundleAdjust(const std::shared_ptr<KeyFrame>& kf, std::unique_lock<std::mutex>& lock) {
  const FrameGeometry& g = *geometry_;
  // Collect under the lock: the window, its points, and the keyframes that see them but stay fixed.
  std::vector<std::shared_ptr<KeyFrame>> kfs;
  std::unordered_map<KeyFrame*, int> kf_index;
  auto addKf = [&](KeyFrame* k, bool fixed, BaProblem& ba) {
    if (kf_index.count(k)) return;
    kf_index[k] = static_cast<int>(ba.keyframes.size());
    kfs.push_back(map_.keyFrame(k));
    ba.keyframes.push_back({k->id, k->T_cam_world(), fixed || !k->parent});
  };
  BaProblem ba;
  addKf(kf.get(), false, ba);
  for (KeyFrame* nb : kf->bestCovisibles(config_.mapping.ba_window))
    if (!nb->bad) addKf(nb, false, ba);
  const std::size_t num_local = ba.keyframes.size();
  if (num_local < 2) return;
  std::vector<std::shared_ptr<MapPoint>> pts;
  std::unordered_map<const MapPoint*, int> pt_index;
  for (std::size_t k = 0; k < num_local; ++k) {
    for (const auto& mp : kfs[k]->points) {
      if (!mp || mp->bad || pt_index.count(mp.get())) continue;
      // A point believed to move would pull the keyframes along with it.
      if (config_.dynamic.mode != DynamicMode::kNone && mp->moving_probability > config_.dynamic.threshold)
        continue;
      pt_index[mp.get()] = static_cast<int>(pts.size());
      pts.push_back(mp);
      ba.points.push_back({mp->id, mp->p_world});
    }
  }
  for (const auto& mp : pts) {
    // As in the pose: unproven points do not pull the keyframes (their own position is still refined).
    const bool mature = isMature(*mp, config_.pose);
    for (const auto& [other, idx] : mp->observations) {
      if (other->bad) continue;
      addKf(other, true, ba);
      const Features& f = *other->features;
      BaObservation o;
      o.keyframe = kf_index.at(other);
      o.point = pt_index.at(mp.get());
      o.uv = f.un[idx];
      o.u_right = f.uRight(g, idx);
      o.information = g.pyramid.inv_sigma2[f.level(idx)];
      o.weight = f.weight[idx] * (mature ? 1.0 : config_.pose.young_point_weight);
      ba.observations.push_back(o);
    }
  }
  bool any_fixed = false;
  for (const auto& k : ba.keyframes) any_fixed = any_fixed || k.fixed;
  if (!any_fixed) {  // gauge freedom: hold the oldest keyframe
    auto oldest = std::min_element(ba.keyframes.begin(), ba.keyframes.end(),
                                   [](const BaKeyFrame& a, const BaKeyFrame& b) { return a.id < b.id; });
    oldest->fixed = true;
  }
  const PoseCamera camera{g.fx, g.fy, g.cx, g.cy, g.bf};

  lock.unlock();  // the tracker keeps running during the solve
  solveLocalBa(ba, camera, config_.mapping, config_.pose);
  lock.lock();

  for (const auto& o : ba.observations) {
    if (!o.outlier) continue;
    KeyFrame* k = kfs[o.keyframe].get();
    const auto& mp = pts[o.point];
    if (!k->bad && !mp->bad) map_.eraseObservation(k, mp);
  }
  std::vector<KeyFramePose> moved;
  for (std::size_t k = 0; k < ba.keyframes.size(); ++k) {
    if (ba.keyframes[k].fixed || kfs[k]->bad) continue;
    kfs[k]->setPose(ba.keyframes[k].T_cam_world.inverse());
    moved.push_back({kfs[k]->id, kfs[k]->stamp, kfs[k]->T_world_cam()});
  }
  for (std::size_t i = 0; i < pts.size(); ++i) {
    if (pts[i]->bad) continue;
    pts[i]->p_world = ba.points[i].p_world;
    pts[i]->updateNormalAndDepth(g);
  }
  std::lock_guard<std::mutex> updates_lock(updates_mutex_);
  updates_.insert(updates_.end(), moved.begin(), moved.end());
}

int LocalMapper::triangulate(KeyFrame* kf, std::unique_lock<std::mutex>& lock) {
  const FrameGeometry& g = *geometry_;
  const auto& th = config_.pose;
  int created = 0;
  const Eigen::Vector3d c1 = kf->center();
  const auto neighbours = kf->bestCovisibles(config_.mapping.triangulation_neighbors);
  std::vector<std::shared_ptr<KeyFrame>> held;  // alive while the lock is let go between neighbours
  for (KeyFrame* nb : neighbours) held.push_back(map_.keyFrame(nb));
  for (const auto& nb_shared : held) {
    if (!nb_shared) continue;
    yieldLock(lock);
    KeyFrame* nb = nb_shared.get();
    if (nb->bad || kf->bad) continue;
    if ((nb->center() - c1).norm() < config_.tracking.virtual_baseline_m) continue;
    const auto pairs = matchForTriangulation(*kf, *nb, g, config_.tracking.match_threshold_low, 0.6,
                                             config_.matcher.epipolar_chi2);
    const Features& f1 = *kf->features;
    const Features& f2 = *nb->features;
    for (const auto& [i1, i2] : pairs) {
      if (kf->points[i1] || nb->points[i2] || kf->dynamic[i1] || nb->dynamic[i2]) continue;
      // Rays in the world frame; too little parallax is left to depth (or nothing).
      const Eigen::Vector3d x1((f1.un[i1].x() - g.cx) / g.fx, (f1.un[i1].y() - g.cy) / g.fy, 1.0);
      const Eigen::Vector3d x2((f2.un[i2].x() - g.cx) / g.fx, (f2.un[i2].y() - g.cy) / g.fy, 1.0);
      const Eigen::Vector3d r1 = kf->T_world_cam().rotation() * x1, r2 = nb->T_world_cam().rotation() * x2;
      const double cos_parallax = r1.dot(r2) / (r1.norm() * r2.norm());
      Eigen::Vector3d p;
      if (f1.depth[i1] > 0 && (cos_parallax > 0.9998 || f1.depth[i1] < f2.depth[i2] || f2.depth[i2] <= 0)) {
        p = kf->T_world_cam() * (x1 * f1.depth[i1]);
      } else if (f2.depth[i2] > 0 && cos_parallax > 0.9998) {
        p = nb->T_world_cam() * (x2 * f2.depth[i2]);
      } else if (cos_parallax < 0.9998 && cos_parallax > 0.0) {
        // Linear triangulation (DLT) from the two projection rows of each view.
        Eigen::Matrix4d A;
        const Eigen::Matrix<double, 3, 4> P1 = kf->T_cam_world().matrix().topRows<3>();
        const Eigen::Matrix<double, 3, 4> P2 = nb->T_cam_world().matrix().topRows<3>();
        A.row(0) = x1.x() * P1.row(2) - P1.row(0);
        A.row(1) = x1.y() * P1.row(2) - P1.row(1);
        A.row(2) = x2.x() * P2.row(2) - P2.row(0);
        A.row(3) = x2.y() * P2.row(2) - P2.row(1);
        const Eigen::Vector4d h = Eigen::JacobiSVD<Eigen::Matrix4d>(A, Eigen::ComputeFullV).matrixV().col(3);
        if (std::abs(h[3]) < 1e-12) continue;
        p = h.head<3>() / h[3];
      } else {
        continue;
      }
      // In front of both, reprojects within chi-square, and consistent distance ratio vs scale ratio.
      const PoseCamera cam{g.fx, g.fy, g.cx, g.cy, g.bf};
      bool ok = true;
      for (int view = 0; view < 2 && ok; ++view) {
        const KeyFrame* k = view == 0 ? kf : nb;
        const Features& f = view == 0 ? f1 : f2;
        const int idx = view == 0 ? i1 : i2;
        if ((k->T_cam_world() * p).z() <= 0) ok = false;
        PoseObservation o{p, f.un[idx], f.uRight(g, idx), g.pyramid.inv_sigma2[f.level(idx)], 1.0, false};
        if (ok && poseChi2(k->T_cam_world(), o, cam) > (o.u_right >= 0 ? th.chi2_rgbd : th.chi2_mono))
          ok = false;
      }
      if (!ok) continue;
      const double d1 = (p - c1).norm(), d2 = (p - nb->center()).norm();
      if (d1 <= 0 || d2 <= 0) continue;
      const double ratio_dist = d2 / d1;
      const double ratio_octave = g.pyramid.scale[f1.level(i1)] / g.pyramid.scale[f2.level(i2)];
      const double factor = 1.5 * g.pyramid.factor;
      if (ratio_dist * factor < ratio_octave || ratio_dist > ratio_octave * factor) continue;
      auto mp = std::make_shared<MapPoint>(map_.newPointId(), p, f1.descriptors.row(i1), kf->id);
      mp->moving_probability = std::max(kf->moving[i1], nb->moving[i2]);
      map_.addPoint(mp);
      map_.addObservation(kf, i1, mp);
      map_.addObservation(nb, i2, mp);
      mp->reference = kf;
      mp->updateDescriptor();
      mp->updateNormalAndDepth(g);
      recent_points_.push_back(mp);
      ++created;
    }
  }
  return created;
}

}  // namespace bmp::tracker

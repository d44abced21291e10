#pragma once
// A keyframe: a frame's features and pose kept in the map, its map points and its covisibility edges.
// Guarded by the Map's mutex like everything in the map.
#include <cstdint>
#include <map>
#include <memory>
#include <set>
#include <vector>

#include "bmp/common/se3.hpp"
#include "tracker/frame.hpp"
#include "tracker/map_point.hpp"

namespace bmp::tracker {

class KeyFrame {
 public:
  KeyFrame(int64_t id, const Frame& frame);

  const int64_t id;
  const int64_t seq;
  const double stamp;
  const std::shared_ptr<const Features> features;
  std::vector<std::shared_ptr<MapPoint>> points;  // per keypoint
  std::vector<float> moving;                      // per keypoint P(dynamic) when it was made (Frame::moving)
  std::vector<uint8_t> dynamic;                   // per keypoint: over the threshold, so no new points here
  // The box observation its frame took from stand-in boxes (empty otherwise): its own answer, when it comes
  // late, replaces it (DynamicStage::observeLate) instead of counting twice.
  std::vector<int8_t> stand_in_z;
  // Its frame's geometric verdicts (Frame::moved; empty before kGeometric's): a late answer's evidence that a
  // chair or cup box moves, as the frame after it takes this frame's.
  std::vector<int8_t> moved;

  void setPose(const SE3& T_world_cam);
  const SE3& T_world_cam() const { return T_world_cam_; }
  const SE3& T_cam_world() const { return T_cam_world_; }
  Eigen::Vector3d center() const { return T_world_cam_.translation(); }

  // Covisibility: keyframes sharing at least `min_weight` points (or the best one).
  std::map<KeyFrame*, int, KeyFrameIdLess> connections;
  std::vector<KeyFrame*> best_covisible;  // by decreasing weight
  std::vector<KeyFrame*> bestCovisibles(int n) const;
  int weight(KeyFrame* other) const;
  void sortConnections();

  // Spanning tree: a culled keyframe's children move to its parent (Map::eraseKeyFrame).
  std::shared_ptr<KeyFrame> parent;
  std::set<KeyFrame*, KeyFrameIdLess> children;
  bool bad = false;

  // Map points observed by at least min_observations keyframes.
  int trackedPoints(int min_observations) const;
  double medianDepth() const;

 private:
  SE3 T_world_cam_ = SE3::Identity();
  SE3 T_cam_world_ = SE3::Identity();
};

}  // namespace bmp::tracker

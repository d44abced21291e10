#pragma once
// The tracker: one call per RGB-D frame. Read Tracker::track first; it is the algorithm's summary.
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

#include <opencv2/core.hpp>

#include "bmp/common/camera_model.hpp"
#include "bmp/common/se3.hpp"
#include "bmp/common/tum_trajectory.hpp"
#include "tracker/dynamic_stage.hpp"
#include "tracker/frame.hpp"
#include "tracker/frame_refiner.hpp"
#include "tracker/held_boxes.hpp"
#include "tracker/local_mapper.hpp"
#include "tracker/map.hpp"
#include "tracker/motion_prior.hpp"
#include "tracker/orb_extractor.hpp"
#include "tracker/tracker_options.hpp"

namespace bmp::tracker {

// Numbered as slam_pose_t's STATE_* constants.
enum class TrackingState : int8_t { kInitialising = 0, kOk = 1, kLost = 2, kRelocalised = 3 };
const char* toString(TrackingState state);

struct TrackerInput {
  double stamp = 0.0;  // seconds
  int64_t seq = 0;
  cv::Mat image;  // CV_8UC3 BGR or CV_8UC1 gray, distorted as captured
  cv::Mat depth;  // CV_16UC1 (units of 1/depth_scale m) or CV_32FC1 metres, registered to image; may be empty
  KeypointWeightFn keypoint_weight;  // optional: per-keypoint weight, 0 excludes
  cv::Mat exclusion_mask;            // optional CV_8UC1: keypoints on nonzero pixels are excluded
  // The detector's boxes for this frame (distorted pixels), when they came: the dynamic stage's
  // observation. Without them the moving probabilities are carried on from the matches.
  std::optional<std::vector<ObjectBox>> boxes;
  // The boxes are an earlier frame's answer standing in for this frame's (real time, stand_in_boxes.hpp):
  // they say nothing new about who the detector found, so no box is held or let go on their word.
  bool boxes_stand_in = false;
};

// After a gap, whether the motion model's pose was checked against the reference keyframe's
// (tracking.recheck_*) and which was kept.
enum class GapRecheck : uint8_t { kNone, kMotionKept, kReferenceTaken };
const char* toString(GapRecheck recheck);

// Where the frame's first pose came from, before the local map search refined it.
enum class PoseSource : uint8_t { kNone, kMapStart, kMotionModel, kReferenceKeyFrame, kRelocalisation };
const char* toString(PoseSource source);

struct TrackResult {
  double stamp = 0.0;
  int64_t seq = 0;
  TrackingState state = TrackingState::kInitialising;
  SE3 T_world_cam = SE3::Identity();  // meaningful when state is kOk or kRelocalised
  int num_keypoints = 0;
  int num_tracked = 0;   // inlier matches to map points used in the pose
  int num_excluded = 0;  // keypoints excluded by the weight hook or mask
  int num_dynamic = 0;   // keypoints the dynamic stage kept out of the pose (P(dynamic) over threshold)
  // Tracked frames: how well the pose's inliers pin the camera's position, the standard deviation (m) of its
  // worst-determined direction at the keypoints' level sigmas (pose_optimizer.hpp positionStd); infinity
  // when not tracked.
  double position_std_m = std::numeric_limits<double>::infinity();
  int num_map_points = 0;
  int num_keyframes = 0;
  int64_t reference_keyframe_id = -1;
  std::optional<KeyFramePose> new_keyframe;    // made from this frame
  std::vector<KeyFramePose> keyframe_updates;  // poses moved by local BA since the previous frame
  cv::Mat dynamic_mask;                        // with new_keyframe: CV_8UC1, 255 on movers (for the mapper)
  // Every keypoint (distorted pixels) and whether the dynamic stage kept it out of the pose: to score the
  // stage against ground-truth masks (precision, recall).
  std::vector<cv::Point2f> keypoints;
  std::vector<uint8_t> keypoint_dynamic;
  // The region test's verdict on each keypoint this frame (empty: no boxes), to tell why one was missed.
  std::vector<uint8_t> keypoint_in_region;
  // Whether each keypoint was a pose inlier (matched to a map point, not an outlier, not dynamic): a mover's
  // keypoint that is one pulls the camera along with it.
  std::vector<uint8_t> keypoint_in_pose;
  GapRecheck gap_recheck = GapRecheck::kNone;
  PoseSource pose_source = PoseSource::kNone;  // kNone: not tracked
  // Inliers of that first pose: a low count before a good local map search is a warning.
  int first_inliers = 0;
  double since_last_s = 0.0;   // after the last tracked frame (0 for the first): frames dropped make it long
  double extract_ms = 0.0;     // ORB extraction
  double lock_wait_ms = 0.0;   // waiting for local mapping to let go of the map
  double dynamic_ms = 0.0;     // the dynamic stage: observations, priors, geometric test, keyframe mask
  double processing_ms = 0.0;  // the whole call
  bool ok() const { return state == TrackingState::kOk || state == TrackingState::kRelocalised; }
};

class Tracker {
 public:
  Tracker(const CameraIntrinsics& camera, const TrackerConfig& config);
  ~Tracker();
  Tracker(const Tracker&) = delete;
  Tracker& operator=(const Tracker&) = delete;

  TrackResult track(const TrackerInput& input);

  // Lets local mapping finish its queue and stops its thread; track() must not be called afterwards.
  void finish();
  // Every tracked frame, placed through its reference keyframe's latest pose (so BA corrections count).
  Trajectory trajectory();
  Trajectory keyFrameTrajectory();
  TrackingState state() const { return state_; }
  // Drops the constant-velocity prediction and the position prior's velocity (lost, relocalised, or the
  // input went back in time).
  void forgetMotion() {
    velocity_.reset();
    motion_prior_.reset();
  }
  // Boxes that came after their frame was tracked: if that frame made a keyframe, its keypoints and map
  // points take the observation. Returns whether a keyframe of that seq was found. For one stream of frames
  // (offline runs); a process whose capture may restart (seq from 0 again) names the keyframe by id.
  bool applyLateBoxes(int64_t seq, const std::vector<ObjectBox>& boxes);
  // The same for keyframe `id`; false when it was culled.
  bool applyLateBoxesToKeyFrame(int64_t id, const std::vector<ObjectBox>& boxes);
  // The dynamic mask of keyframe id as it stands now (after late boxes); empty when it was culled.
  cv::Mat keyframeMask(int64_t id, const std::vector<ObjectBox>* boxes, const cv::Mat& depth);
  const FrameGeometry& geometry() const { return *geometry_; }
  const TrackerConfig& config() const { return config_; }

 private:
  // A tracked frame's velocity and the motion prior's sample (OK), or none after relocalisation.
  void followMotion(const Frame& frame);
  Frame makeFrame(const TrackerInput& input, const std::optional<std::vector<ObjectBox>>& boxes,
                  TrackResult& result) const;
  bool initialise(Frame& frame, TrackResult& result);
  // Priors and box observation into the frame's moving probabilities, then the pose without the
  // dynamic keypoints (and, if asked, how well it is pinned: optimizeFramePose).
  void optimizePose(Frame& frame, double* position_std_m = nullptr);
  // The motion model, else the reference keyframe; after a gap, the better of the two
  // (tracking.recheck_*).
  bool trackFromLastFrame(Frame& frame, TrackResult& result);
  bool trackWithMotionModel(Frame& frame);
  bool trackReferenceKeyFrame(Frame& frame);
  bool relocalise(Frame& frame);
  bool trackLocalMap(Frame& frame);
  void updateLocalMap(const Frame& frame);
  bool needNewKeyFrame(const Frame& frame) const;
  // A keyframe of the local map already sees from about where the frame is (keyframes.revisit_*).
  bool placeIsMapped(const Frame& frame) const;
  // The frame is about where its reference keyframe was taken (keyframes.still_*).
  bool atRestOnReference(const Frame& frame) const;
  void insertKeyFrame(Frame& frame, TrackResult& result);
  void prepareLastFrame();
  void rememberFrame(const Frame& frame);
  // The frames whose reference keyframe has settled get their second look (frame_refiner.hpp); with all,
  // every frame still waiting. The caller holds the map lock.
  void refineSettledFrames(bool all);
  int countTracked(const Frame& frame) const;
  // The frame's person boxes, where the keypoint budget is spent sparingly (every mode with boxes).
  SparseRegions sparseRegions(const std::optional<std::vector<ObjectBox>>& boxes) const;
  bool inPose(const Frame& frame, std::size_t i) const;

  // A tracked frame, relative to its reference keyframe by id: holding the keyframe itself would keep
  // every culled keyframe and its features alive for the whole run. One per frame for the whole run, so
  // kept small (48 bytes, not an Isometry3d's 144): the pose relative to a nearby keyframe needs no
  // double precision (float: under a micrometre and a microradian at a few metres).
  struct FrameRecord {
    FrameRecord(double stamp, int64_t reference_id, const SE3& T_ref_cam, float position_std_m);
    SE3 T_ref_cam() const;
    double stamp;
    int64_t reference_id;
    Eigen::Vector3f t_ref_cam;
    float position_std_m;  // the tracked pose's (TrackResult): the weight trajectory_smoother.hpp gives it
    Eigen::Quaternionf q_ref_cam;
  };
  static_assert(sizeof(FrameRecord) <= 48, "a frame record is kept for every frame of the run");
  SE3 recordPose(const FrameRecord& r) const;  // T_world_cam, by its reference keyframe as it stands now

  TrackerConfig config_;
  std::shared_ptr<const FrameGeometry> geometry_;
  OrbExtractor extractor_;
  DynamicStage dynamic_;
  HeldBoxes held_boxes_;  // persons the detector missed this frame, found just before
  Map map_;               // declared before the mapper, which uses it
  std::unique_ptr<LocalMapper> mapper_;
  TrackingState state_ = TrackingState::kInitialising;
  Frame last_frame_;
  SE3 last_T_ref_cam_ = SE3::Identity();  // last frame relative to its reference keyframe
  std::optional<SE3> velocity_;           // T_last_current of the previous step ...
  double velocity_dt_ = 0.0;              // ... which spanned this many seconds
  MotionPrior motion_prior_;
  std::optional<PositionPrior> position_prior_;  // the current frame's, when predicted by constant velocity
  std::shared_ptr<KeyFrame> reference_kf_;
  std::vector<std::shared_ptr<KeyFrame>> local_keyframes_;
  std::vector<std::shared_ptr<MapPoint>> local_points_;
  int64_t last_keyframe_seq_ = 0;
  int64_t last_reloc_seq_ = -1000000;
  double dynamic_ms_ = 0.0;  // the current frame's time in the dynamic stage, spread over several steps
  std::deque<FrameRecord> records_;               // a deque: no copy of the whole run's records when it grows
  std::vector<std::size_t> relocalised_records_;  // records where tracking began again after a loss
  FrameRefiner refiner_;  // frames waiting for their second look, by index into records_
};

}  // namespace bmp::tracker

#pragma once
// The built-in synthetic sequence: a textured box room with furniture, seen by a smoothly moving RGB-D
// camera, with movers walking through it: person-sized textured boxes, or people cut out of real photos
// (billboards facing the camera) that a person detector recognises. Renders colour, exact z-depth,
// ground-truth poses, masks of the moving objects and which mover each pixel shows, deterministically from
// a seed. World frame: z up, floor at z = 0, room centred on the origin in x and y. Camera frame: z
// forward, x right, y down.
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "bmp/common/camera_model.hpp"
#include "bmp/common/se3.hpp"
#include "bmp/common/tum_trajectory.hpp"

namespace bmp::capture {

// What moves through the room (README, "bmp-capture"; config/synthetic/*.yaml).
enum class SyntheticScenario {
  kBoxes,          // num_moving_objects textured boxes walking loops (the default)
  kPeopleWalking,  // num_moving_objects people (1..3) pacing across the view at different depths
  kPersonStops,    // one person walks in, stands still for 3 s, walks on
  kCrowd,          // ten people in two rows cross the view, covering most of it for over 2 s
  kUnknownMover,   // one textured box (a class no detector knows) and one person
};
// "boxes", "people_walking", "person_stops", "crowd", "unknown_mover"; parse throws std::invalid_argument.
SyntheticScenario parseScenario(const std::string& name);
std::string toString(SyntheticScenario scenario);
const std::vector<std::string>& scenarioNames();

// A person for the person movers: a photo in the shared folder and the person's box in it. The person is
// segmented inside the box when the scene is built; the box's height becomes height_m in the room.
struct PersonSource {
  std::string image;          // relative to the shared folder ($BMP_SHARED, else ../shared), or absolute
  std::array<int, 4> rect{};  // x, y, width, height in image pixels
  double height_m = 1.7;
};
// The built-in people: full-length people in the shared sample photos (images/README.md).
std::vector<PersonSource> defaultPeople();

struct SyntheticSceneConfig {
  CameraIntrinsics camera;  // pinhole only: distortion is ignored
  int num_frames = 300;
  double fps = 30.0;
  double start_stamp = 1000.0;  // seconds; frame i is at start_stamp + i / fps (rounded to microseconds)
  int64_t seed = 1;

  std::array<double, 3> room_size{6.0, 5.0, 3.0};  // x, y, height (m)
  int num_static_boxes = 5;                        // furniture pieces along the walls, 0..5
  double texels_per_metre = 200.0;                 // texture resolution
  double shapes_per_square_metre = 110.0;          // density of drawn texture shapes

  // Camera path: centre plus a sinusoid per axis; orientation looks along +y, then yaw, pitch, roll.
  std::array<double, 3> camera_centre{0.0, -1.6, 1.4};
  std::array<double, 3> camera_amplitude{0.7, 0.3, 0.15};        // m
  std::array<double, 3> camera_period{11.0, 7.0, 5.0};           // s
  double base_pitch_deg = -8.0;                                  // negative looks down
  std::array<double, 3> rotation_amplitude_deg{18.0, 8.0, 6.0};  // yaw, pitch, roll
  std::array<double, 3> rotation_period{9.0, 6.5, 8.0};          // s
  double camera_ramp_s = 0.0;  // s; > 0: the sinusoids grow from rest to their amplitudes over this time

  SyntheticScenario scenario = SyntheticScenario::kBoxes;
  int num_moving_objects = 2;                          // boxes, or people in people_walking
  std::array<double, 3> object_size{0.5, 0.5, 1.7};    // width, depth, height (m) of box movers
  double walk_speed = 1.0;                             // m/s
  std::vector<PersonSource> people = defaultPeople();  // used in turn by the person movers

  double max_depth = 8.0;    // m; farther pixels get depth 0
  double depth_noise = 0.0;  // m, standard deviation at 1 m, growing with depth squared
  double color_noise = 1.5;  // grey levels, standard deviation per channel
  // Motion blur: the colour image is the mean of exposure_samples renders spread over exposure_s, centred
  // on the frame's stamp, as a sensor integrating light while the camera and the movers move (0: a still
  // image). Depth, masks and the pose stay those of the stamp.
  double exposure_s = 0.0;
  int exposure_samples = 5;
};

enum class MoverKind { kBox, kPerson };

// One mover at one frame: which it is and what it does.
struct MoverInfo {
  int id = 1;  // the value of its pixels in SyntheticFrame::mover_ids
  MoverKind kind = MoverKind::kBox;
  bool moving = true;  // false while it stands still
};

struct SyntheticFrame {
  int index = 0;
  double stamp = 0.0;
  cv::Mat bgr;                    // CV_8UC3
  cv::Mat depth;                  // CV_16UC1, depth_scale units per metre, 0 = no measurement
  cv::Mat mask;                   // CV_8UC1, 255 on moving objects
  cv::Mat mover_ids;              // CV_8UC1, 0 on the static scene, MoverInfo::id on each mover's pixels
  std::vector<MoverInfo> movers;  // every mover of the scene, in view or not, in id order
  SE3 T_world_cam = SE3::Identity();
};

// An axis-aligned box in the world (room, furniture) or in an object's own frame.
struct AlignedBox {
  Eigen::Vector3d lo = Eigen::Vector3d::Zero();
  Eigen::Vector3d hi = Eigen::Vector3d::Zero();
};

// A walking object at one instant: box [-d/2, d/2] x [-w/2, w/2] x [0, h] rotated by yaw about z. A person
// is the flat box x = 0 (a billboard) whose +x side faces the camera; only its silhouette is drawn.
struct MovingObjectState {
  Eigen::Vector2d position = Eigen::Vector2d::Zero();  // centre on the floor
  double yaw = 0.0;                                    // radians about world z
  SE3 T_world_object = SE3::Identity();
  AlignedBox box;  // in the object frame
  MoverInfo info;
};

class SyntheticScene {
 public:
  // Builds every texture up front (a few hundred milliseconds); rendering is then cheap.
  explicit SyntheticScene(const SyntheticSceneConfig& config);
  ~SyntheticScene();
  SyntheticScene(SyntheticScene&&) noexcept;
  SyntheticScene& operator=(SyntheticScene&&) noexcept;

  // Throws std::out_of_range outside [0, numFrames()).
  SyntheticFrame render(int index) const;
  int numFrames() const { return config_.num_frames; }
  const CameraIntrinsics& camera() const { return config_.camera; }
  const SyntheticSceneConfig& config() const { return config_; }

  double stamp(int index) const;
  SE3 cameraPose(int index) const;
  Trajectory groundTruth() const;

  // Geometry, for tests and visualisation.
  const AlignedBox& room() const { return room_; }
  const std::vector<AlignedBox>& staticBoxes() const { return static_boxes_; }
  std::vector<MovingObjectState> movingObjects(int index) const;

 private:
  std::vector<MovingObjectState> movingObjectsAt(double t) const;
  // Frame index's image as seen at t seconds from the start (index picks the noise).
  SyntheticFrame renderAt(int index, double t) const;

  SyntheticSceneConfig config_;
  AlignedBox room_;
  std::vector<AlignedBox> static_boxes_;
  struct Internals;  // textures, walking paths, people, motion phases, noise tile
  std::unique_ptr<Internals> in_;

  void buildBoxWalkers();
  void buildCast();
};

}  // namespace bmp::capture

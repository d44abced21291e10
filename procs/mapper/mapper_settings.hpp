#pragma once
// Every tunable of the mapper library, with its default. config/mapper.yaml names each once; the process
// fills this struct from it (mapper_config.hpp) and the library never opens a file.
#include <array>

namespace bmp::mapper {

// Which pixels of a keyframe become map points.
struct CloudSettings {
  double min_depth_m = 0.3;  // nearer depth is dropped (sensor noise, the robot itself)
  double max_depth_m = 5.0;  // farther depth is dropped (noise grows with depth squared)
  int mask_dilation_px = 5;  // dynamic mask grown by this many pixels: mask edges miss the mover's rim
  int pixel_step = 1;        // back-project every Nth pixel in each direction (1..kMaxPixelStep)
  static constexpr int kMaxPixelStep = 16;
  double keyframe_voxel_m = 0.02;  // voxel filter of one keyframe's cloud (camera frame)
  double map_voxel_m = 0.02;       // voxel filter of the stitched global cloud
  double viewer_voxel_m = 0.05;    // the down-sampled cloud published for viewers
  // A cloud point whose octree leaf has been seen through until its occupancy probability fell below this is
  // left out of the cloud: a mover's rim the mask missed is carved by later views of the space behind it.
  // 0 keeps every point.
  double drop_carved_below = 0.2;
};

// The OctoMap occupancy octree.
struct OctomapSettings {
  double resolution_m = 0.05;
  // Rays longer than this are cut there (free space only, no hit). A point's ray is longer than its depth off
  // the optical axis (1.26 x at a 640x480 image's corner, f 525): cloud.max_depth_m 5 needs 6.3.
  double max_range_m = 6.3;
  double prob_hit = 0.7;  // OctoMap's sensor model
  double prob_miss = 0.4;
  double clamp_min = 0.1192;
  double clamp_max = 0.971;
  double occupied_threshold = 0.5;
};

// When a pose update makes the octree rebuild from the stored keyframe clouds.
struct RebuildSettings {
  double min_interval_s = 5.0;      // at most once per interval (a rebuild re-casts every keyframe's rays)
  double min_translation_m = 0.02;  // only when some keyframe moved more than this ...
  double min_rotation_deg = 1.0;    // ... or turned more than this
};

// Revisits: a keyframe whose pose lies this close to a stored keyframe's sees mostly what that one saw. Its
// rays carve the octree as usual (that is how ghosts clear); its cloud is folded into the stored keyframe's
// and voxel-filtered again, so mapping the same room over and over keeps memory bounded. 0 for both: every
// keyframe keeps its own cloud.
struct MergeSettings {
  double max_translation_m = 0.05;
  double max_rotation_deg = 5.0;
  // A stored keyframe keeps its newest revisits' rays as scans of their own, so a rebuild casts them as they
  // were cast: a point the revisits saw through (a person who left) stays cleared. Folded into one scan, a
  // cell both hit and passed through counts as hit, and the person came back with every rebuild. Older
  // revisits' rays are folded into the keyframe's own beyond this many (memory stays bounded).
  int max_scans = 4;
};

// The floor the grid stands on. The tracker's world is its first camera's frame (x right, y down, z
// forward): `up` is then only a guess (-y; a camera looking down tilts it), so by default the floor is
// fitted in the cloud: the lowest plane within max_tilt_deg of up that holds at least min_share of the
// points. Its normal becomes up, its height the zero of the grid's height band.
enum class FloorMode { kFit, kFixed };
struct FloorSettings {
  FloorMode mode = FloorMode::kFit;
  double height_m = -1.0;  // fixed floor, or the fallback while none is found: along up from the origin
  double max_tilt_deg = 30.0;
  double inlier_m = 0.03;      // a point this close to a plane supports it
  double min_share = 0.05;     // of the cloud's points, for a plane to count as the floor
  int iterations = 1000;       // RANSAC samples (deterministic: a fixed seed)
  int max_points = 20000;      // the cloud is sub-sampled to this many points for the fit
  double sample_cell_m = 0.3;  // a sample's three points come from one cell this size: one surface's
};

// The 2-D occupancy grid: the octree between two heights above the floor, projected along up onto it.
struct GridSettings {
  double resolution_m = 0.05;
  std::array<double, 3> up{0.0, -1.0, 0.0};  // world direction of "up"; normalised when read
  double height_min_m = 0.1;                 // the band above the floor that can block a robot
  double height_max_m = 1.5;
  // Where the camera was, its carrier stood: the floor around each kept keyframe's camera is free in the
  // grid where nothing else is known (the camera never sees the column under itself, so a planner refused
  // to start from the robot's own position). Never over an occupied cell. 0: off.
  double camera_free_radius_m = 0.2;
  FloorSettings floor;
  // Not configured: the up the grid's axes are chosen by (PlaneFrame). groundedGrid keeps the configured up
  // here when `up` becomes the fitted floor's normal. Zero: `up` itself.
  std::array<double, 3> axes_from{0.0, 0.0, 0.0};
};

// Pictures written beside the map files.
struct PictureSettings {
  int size_px = 1000;                   // longer side of the cloud pictures
  int grid_cell_px = 4;                 // pixels per grid cell in the grid picture
  double oblique_elevation_deg = 35.0;  // the oblique view's angle above the floor plane
  double oblique_azimuth_deg = -60.0;   // its direction around the up axis
  double cut_above_m = 1.0;  // points higher than grid.height_max_m + this are left out (the ceiling)
};

struct MapperSettings {
  CloudSettings cloud;
  OctomapSettings octomap;
  RebuildSettings rebuild;
  MergeSettings merge;
  GridSettings grid;
  PictureSettings pictures;
  // Keyframes (and pose updates) farther than this from the world origin (the tracker's first camera) are
  // refused: the 2-D grid spans every keyframe, so one forged pose 1.6 km away would ask for a grid of
  // 64000^2 cells. 200 m (plus 5 m of range) at 5 cm cells bounds the grid to about 8200^2 cells (67 MB).
  double world_radius_m = 200.0;
  // Keyframes kept on their own (revisits merged into one are not counted). When the map holds this many, a
  // keyframe that is not a revisit is refused: a stream of forged keyframes with fresh ids cannot grow the
  // mapper's memory without bound. At the defaults a keyframe holds about 2 MiB (Bonn: 60 keyframes,
  // 121 MiB more resident), so 4000 is about 8 GiB.
  int max_keyframes = 4000;
};

}  // namespace bmp::mapper

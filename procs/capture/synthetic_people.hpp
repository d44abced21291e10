#pragma once
// People for the synthetic scene's person movers, cut out of real photos in the shared folder (read in
// place, never copied): the person inside the configured box is segmented once, when the scene is built,
// so that only the silhouette is drawn and the photo's background never enters the room.
#include <opencv2/core.hpp>

#include "capture/synthetic_scene.hpp"

namespace bmp::capture::synth {

struct PersonCutout {
  // Both stored bottom row first (row 0 at the feet), the way billboard texture coordinates run upwards.
  cv::Mat bgr;    // CV_8UC3; background pixels hold the person's mean colour, so mip levels do not bleed
  cv::Mat alpha;  // CV_8UC1, 255 on the person, 0 elsewhere
  double width_m = 0.0, height_m = 0.0;
  double texels_per_metre = 1.0;
};

// Reads the photo (path resolved against the shared folder), segments the person inside source.rect with
// GrabCut and keeps the largest connected region, holes filled. Deterministic. Throws std::runtime_error
// naming the file when it is missing or unreadable, when the box does not lie inside it, or when little
// is left of the person.
PersonCutout cutOutPerson(const PersonSource& source);
// The same person flipped left to right: a second look when a crowd reuses a photo.
PersonCutout mirrored(const PersonCutout& cutout);

}  // namespace bmp::capture::synth

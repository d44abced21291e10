#pragma once
// Pictures of the map, drawn with OpenCV alone: the coloured cloud seen from above and from an oblique
// angle (orthographic, nearest point wins per pixel), and the 2-D grid.
#include <opencv2/core.hpp>

#include "mapper/mapper_settings.hpp"
#include "mapper/occupancy_grid.hpp"
#include "mapper/point_types.hpp"

namespace bmp::mapper {

// Looking down along -up; the plane's x to the right, its y upwards in the picture.
cv::Mat renderTopView(const PointList& cloud, const PlaneFrame& frame, const GridSettings& grid,
                      const PictureSettings& settings);
// Looking down at oblique_elevation_deg from the direction oblique_azimuth_deg (about up, from the plane's
// x).
cv::Mat renderObliqueView(const PointList& cloud, const PlaneFrame& frame, const GridSettings& grid,
                          const PictureSettings& settings);
// The grid picture's largest side: a grid spanning the world's radius at cell_px 4 took 1.6 GB to draw.
inline constexpr int kMaxGridPicturePx = 4096;
// Free white, occupied black, unknown grey, cell_px pixels per cell (fewer, down to a share of one, within
// kMaxGridPicturePx); the plane's y upwards.
cv::Mat renderGrid(const OccupancyGrid2D& grid, int cell_px);

}  // namespace bmp::mapper

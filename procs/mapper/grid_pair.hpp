#pragma once
// occupancy.yaml and the image it names, replaced as a pair. A planner reads the YAML, then the image it
// names; two renames one after the other would let it pair a new YAML (new origin and size) with the old
// image. So each save writes a numbered image that is never rewritten (occupancy.N.pgm), then the YAML naming
// it; the previous save's image stays for a reader still holding the previous YAML, older ones are removed.
// occupancy.pgm, the latest image under a fixed name, is written too, for viewers and scripts.
#include <string>
#include <vector>

#include "mapper/occupancy_grid.hpp"

namespace bmp::mapper {

// Writes the pair into dir (which exists) and returns the paths written. The number follows the highest
// already in dir, so a restarted mapper carries on. Throws FileWriteError naming the file.
std::vector<std::string> writeGridPair(const std::string& dir, const OccupancyGrid2D& grid);

}  // namespace bmp::mapper

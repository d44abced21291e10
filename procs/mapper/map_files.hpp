#pragma once
// Everything the mapper leaves on disk, each file replaced atomically (a temporary beside it, then renamed),
// so a reader or a crash never sees half a map.
#include <string>
#include <vector>

#include "mapper/mapper.hpp"

namespace bmp::mapper {

// map.pcd, map.ply, map.bt, occupancy.N.pgm + occupancy.pgm + occupancy.yaml (grid_pair.hpp), cloud_top.png,
// cloud_oblique.png, occupancy.png.
// Creates dir if needed; brings the mapper up to date first (flush). Returns the paths written. Throws
// FileWriteError (bmp/common/atomic_file.hpp) naming the file that could not be written.
std::vector<std::string> writeMapFiles(const std::string& dir, Mapper& mapper);

// Creates dir if needed and writes (then removes) a file in it. Throws FileWriteError naming dir when either
// fails: a start-up check, so an unwritable map folder stops the mapper before anything is mapped.
void checkMapFolder(const std::string& dir);

}  // namespace bmp::mapper

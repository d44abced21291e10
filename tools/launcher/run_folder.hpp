#pragma once
// A run into a folder an earlier run wrote: the new run must neither mix its files with the earlier ones
// (a trajectory evaluated against another run's ground truth, a map beside another run's logs) nor destroy
// them without a word. The rule, one for every output: the earlier run's whole folder is moved, as one unit,
// into OUT/previous/, replacing the run kept there before; so OUT holds this run and OUT/previous the one
// before it. A non-empty folder that no run wrote is refused, never moved.
#include <string>

namespace bmp::launcher {

// The name of the folder inside a run folder that holds the run before it.
inline constexpr const char* kPreviousRunFolder = "previous";

// Moves what an earlier run left in out_dir (a folder holding logs/, which every run makes first) into
// out_dir/previous/, replacing an older previous/; returns true when it moved something. Nothing to do for a
// missing or empty folder. Throws ArgError naming out_dir when it is a file or a non-empty folder that is
// not a run folder, std::runtime_error naming the file when one cannot be moved.
bool setAsideEarlierRun(const std::string& out_dir);

}  // namespace bmp::launcher

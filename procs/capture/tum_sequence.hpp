#pragma once
// Reading TUM-format sequence folders: rgb.txt, depth.txt and optional groundtruth.txt, with colour/depth
// association as the TUM benchmark's associate.py does it.
#include <stdexcept>
#include <string>
#include <vector>

#include "bmp/common/tum_trajectory.hpp"

namespace bmp::capture {

class SequenceError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// One "timestamp filename" line of rgb.txt or depth.txt.
struct ListEntry {
  double stamp = 0.0;
  std::string path;  // relative to the sequence folder, as written in the list
};

// Parses a TUM list file. Throws SequenceError naming file and line for a malformed line, and for stamps that
// are not seconds. A last line cut off while written is left out and described in cut_last_line, if given.
std::vector<ListEntry> readListFile(const std::string& path, std::string* cut_last_line = nullptr);

struct StampMatch {
  std::size_t first = 0;   // index into the first list
  std::size_t second = 0;  // index into the second list
};

// associate.py: all pairs closer than max_difference, taken greedily by increasing time difference, each
// stamp used once; the result is sorted by the first stamp.
std::vector<StampMatch> associateStamps(const std::vector<double>& first, const std::vector<double>& second,
                                        double max_difference, double offset = 0.0);

struct FramePair {
  double rgb_stamp = 0.0;
  std::string rgb_path;  // absolute or relative to the working directory (folder + list entry)
  double depth_stamp = 0.0;
  std::string depth_path;
};

struct SequenceIndex {
  std::string dir;
  std::string name;                 // folder name
  std::vector<FramePair> frames;    // associated pairs, by colour time
  Trajectory groundtruth;           // empty when the folder has no groundtruth.txt, or a malformed one
  std::string groundtruth_problem;  // why a groundtruth.txt there was not read (file and line), else ""
  std::size_t rgb_entries = 0;      // entries whose file exists
  std::size_t depth_entries = 0;
  // Listed files that do not exist (stamp and path from the sequence's folder); left out before
  // association, so their neighbours can still pair.
  std::vector<ListEntry> missing_files;
  // What was worked around in rgb.txt and depth.txt (a last line cut off while written), file and line.
  std::vector<std::string> list_problems;
};

// Files listed but absent are left out and reported in missing_files (not an error: real datasets have them).
// Throws SequenceError for a missing folder, a missing or malformed list, or no associated pair. A malformed
// groundtruth.txt is not an error: it is left out, with the reason in groundtruth_problem.
SequenceIndex indexSequence(const std::string& dir, double max_difference = 0.02);

}  // namespace bmp::capture

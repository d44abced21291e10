#include "capture/tum_sequence.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <system_error>
#include <tuple>

#include "bmp/common/tum_text_list.hpp"

namespace bmp::capture {

namespace fs = std::filesystem;

namespace {

// Seconds since 1970 stay below this until the year 5138; a larger stamp is in micro- or nanoseconds, and
// would play with every frame interval a million times too long.
constexpr double kLargestStampInSeconds = 1e11;

}  // namespace

std::vector<ListEntry> readListFile(const std::string& path, std::string* cut_last_line) {
  std::vector<ListEntry> entries;
  try {
    for (auto& record : readTumTextList(path, {"list file", "timestamp filename", 1, false}, cut_last_line)) {
      if (std::abs(record.stamp) >= kLargestStampInSeconds)
        throw SequenceError(
            path + ":" + std::to_string(record.line) + ": the stamp in '" + record.text +
            "' is not in seconds (micro- or nanoseconds?); TUM lists give seconds, e.g. "
            "1305031102.175304. For nanoseconds: awk '/^#/ {print; next} {printf \"%.9f %s\\n\", "
            "$1 / 1e9, $2}' " +
            fs::path(path).filename().string() + " > seconds.txt");
      // Frames carry their stamps as microseconds since 1970, which every consumer refuses below 0.
      if (record.stamp < 0)
        throw SequenceError(
            path + ":" + std::to_string(record.line) + ": the stamp in '" + record.text +
            "' is negative; TUM lists give seconds since 1970 (add an offset to every stamp)");
      entries.push_back({record.stamp, std::move(record.fields[0])});
    }
  } catch (const TumTextError& e) {
    throw SequenceError(e.what());
  }
  return entries;
}

std::vector<StampMatch> associateStamps(const std::vector<double>& first, const std::vector<double>& second,
                                        double max_difference, double offset) {
  // Candidate pairs within max_difference; second is searched through a sorted copy so this stays
  // O(n log n) for long sequences, while the greedy choice is exactly associate.py's. Each stamp takes only
  // its kNearest nearest candidates: a real list has one or two within the tolerance, and lists with many
  // near-equal stamps (or a tolerance of hours) would otherwise make every pair a candidate (10000 frames:
  // 5 GB and a minute and a half).
  constexpr std::size_t kNearest = 16;
  std::vector<std::size_t> order(second.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return second[a] < second[b]; });
  std::vector<double> sorted(second.size());
  for (std::size_t i = 0; i < order.size(); ++i) sorted[i] = second[order[i]] + offset;

  std::vector<std::tuple<double, double, double, std::size_t, std::size_t>> candidates;
  for (std::size_t a = 0; a < first.size(); ++a) {
    // Outwards from where first[a] would be, the nearer side first.
    auto lo = std::lower_bound(sorted.begin(), sorted.end(), first[a]);
    auto hi = lo;
    for (std::size_t k = 0; k < kNearest; ++k) {
      const double below = lo != sorted.begin() ? first[a] - *std::prev(lo) : HUGE_VAL;
      const double above = hi != sorted.end() ? *hi - first[a] : HUGE_VAL;
      const bool take_below = below <= above;
      const double diff = take_below ? below : above;
      if (!(diff < max_difference)) break;
      const auto at = take_below ? --lo : hi++;
      const std::size_t b = order[static_cast<std::size_t>(at - sorted.begin())];
      candidates.emplace_back(diff, first[a], second[b], a, b);
    }
  }
  std::sort(candidates.begin(), candidates.end());
  std::vector<bool> used_first(first.size(), false), used_second(second.size(), false);
  std::vector<StampMatch> matches;
  for (const auto& [diff, ta, tb, a, b] : candidates) {
    if (used_first[a] || used_second[b]) continue;
    used_first[a] = used_second[b] = true;
    matches.push_back({a, b});
  }
  std::sort(matches.begin(), matches.end(),
            [&](const StampMatch& x, const StampMatch& y) { return first[x.first] < first[y.first]; });
  return matches;
}

SequenceIndex indexSequence(const std::string& dir, double max_difference) {
  if (!fs::is_directory(dir)) throw SequenceError(dir + ": no such sequence folder");
  const fs::path root(dir);
  for (const char* list : {"rgb.txt", "depth.txt"}) {
    if (!fs::is_regular_file(root / list))
      throw SequenceError(dir + ": not a TUM-format folder (" + list + " is missing)");
  }
  SequenceIndex index;
  const auto existing = [&](const std::string& list) {
    std::vector<ListEntry> kept;
    std::string cut;
    auto entries = readListFile((root / list).string(), &cut);
    if (!cut.empty()) index.list_problems.push_back(cut);
    for (auto& e : entries) {
      // The error_code form: a symlink loop (or a file we may not look at) is a missing file, not an
      // exception that ends the whole run.
      std::error_code unreadable;
      if (fs::is_regular_file(root / e.path, unreadable)) {
        kept.push_back(std::move(e));
      } else {
        index.missing_files.push_back({e.stamp, (root / e.path).string()});
      }
    }
    return kept;
  };
  const auto rgb = existing("rgb.txt");
  const auto depth = existing("depth.txt");
  std::vector<double> rgb_stamps, depth_stamps;
  for (const auto& e : rgb) rgb_stamps.push_back(e.stamp);
  for (const auto& e : depth) depth_stamps.push_back(e.stamp);

  index.dir = dir;
  index.name = fs::absolute(root).lexically_normal().filename().string();
  if (index.name.empty())
    index.name = fs::absolute(root).lexically_normal().parent_path().filename().string();
  index.rgb_entries = rgb.size();
  index.depth_entries = depth.size();
  for (const auto& m : associateStamps(rgb_stamps, depth_stamps, max_difference)) {
    index.frames.push_back({rgb[m.first].stamp, (root / rgb[m.first].path).string(), depth[m.second].stamp,
                            (root / depth[m.second].path).string()});
  }
  if (index.frames.empty()) {
    std::string why = dir + ": no colour/depth pair within " + std::to_string(max_difference) + " s (" +
                      std::to_string(rgb.size()) + " colour and " + std::to_string(depth.size()) +
                      " depth files found";
    // Paths written relative to another folder leave every file missing: say so, with one of them.
    if (!index.missing_files.empty())
      why += "; " + std::to_string(index.missing_files.size()) + " listed files do not exist, such as " +
             index.missing_files.front().path;
    throw SequenceError(why + ")");
  }
  if (fs::is_regular_file(root / "groundtruth.txt")) {
    // The ground truth is optional: a bad line in it (a motion-capture dropout written as nan) must not
    // keep the frames from playing.
    try {
      index.groundtruth = readTumTrajectory((root / "groundtruth.txt").string());
    } catch (const TrajectoryError& e) {
      index.groundtruth_problem = e.what();
    }
  }
  return index;
}

}  // namespace bmp::capture

#pragma once
// The run folder's earlier results: a run into a folder an earlier run wrote must not be judged by that
// run's ground truth, evaluation or plots when it writes none of its own (a folder without ground truth).
#include <string>
#include <vector>

namespace bmp::launcher {

// Renames each earlier result (groundtruth.txt, eval.json, summary.json, plots/) found in out_dir to
// NAME.prev, replacing an older NAME.prev; returns the names moved. Throws std::runtime_error naming the
// file when one cannot be moved: the run must not start beside results it would be confused with.
std::vector<std::string> setAsideEarlierResults(const std::string& out_dir);

}  // namespace bmp::launcher

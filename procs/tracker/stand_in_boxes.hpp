#pragma once
// Real time, a frame whose own answer has not come yet is observed with a stand-in: the newest earlier
// answer, moved on for its age at the image speed its boxes showed since the answer before it, and grown
// for its age. One rule for bmp-tracker and for the benchmark's reproducible emulation of it
// (bmp-bench-tracker --box-lag).
#include <cstdint>
#include <optional>
#include <vector>

#include "tracker/detection_book.hpp"
#include "tracker/dynamic_regions.hpp"
#include "tracker/tracker_options.hpp"

namespace bmp::tracker {

// `before`: the newest usable answers for earlier frames, newest first (DetectionBook::newestBefore, at most
// two are used). nullopt when there is none, or the newest is older than stale_box_max_age_s (the frame is
// then tracked on the probabilities its matches carry).
std::optional<std::vector<ObjectBox>> standInBoxes(const std::vector<FrameBoxes>& before, int64_t frame_utime,
                                                   const DynamicOptions& options);

}  // namespace bmp::tracker

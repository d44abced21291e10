#pragma once
// Real time, a frame whose own answer has not come yet is observed with a stand-in: the newest earlier
// answer, moved on for its age at the image speed its boxes showed since the answer before it, and grown
// for its age. One rule for bmp-tracker and for the benchmark's reproducible emulation of it
// (bmp-bench-tracker --box-lag).
#include <cstddef>
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

// Frame i's stand-in when every answer comes `lag` (>= 1) frames late, as bmp-bench-tracker --box-lag and the
// scenario tests replay real time: the answers of frames i-lag and i-lag-1 through standInBoxes. answers and
// stamps_s (seconds) hold frames 0..i at least.
std::optional<std::vector<ObjectBox>> laggedStandIn(const std::vector<std::vector<ObjectBox>>& answers,
                                                    const std::vector<double>& stamps_s, std::size_t i,
                                                    std::size_t lag, const DynamicOptions& options);

}  // namespace bmp::tracker

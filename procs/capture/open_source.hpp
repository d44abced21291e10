#pragma once
// The frame source capture's settings ask for: the TUM-format folder of --dataset, else the synthetic scene,
// with --start/--end/--every applied.
#include <functional>
#include <memory>
#include <string>

#include "capture/camera_selection.hpp"
#include "capture/capture_settings.hpp"
#include "capture/frame_source.hpp"
#include "capture/tum_sequence.hpp"

namespace bmp::capture {

// Opens it at once, so a missing folder, an unknown camera or a bad scene file fails before any frame is
// played (SequenceError, ConfigError). warn receives one line per frame the source skips.
std::unique_ptr<FrameSource> openFrameSource(const CaptureSettings& settings,
                                             std::function<void(const std::string&)> warn);

// Logs what a TUM folder's reading found, before any frame: the camera file and why it was chosen, a ground
// truth that cannot be used, problems in its lists. bmp-capture and tum2lcm say the same.
void logSequenceFindings(const SequenceIndex& index, const SequenceCamera& camera);

}  // namespace bmp::capture

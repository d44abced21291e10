#pragma once
// The frame source capture's settings ask for: the TUM-format folder of --dataset, else the synthetic scene,
// with --start/--end/--every applied.
#include <functional>
#include <memory>
#include <string>

#include "capture/capture_settings.hpp"
#include "capture/frame_source.hpp"

namespace bmp::capture {

// Opens it at once, so a missing folder, an unknown camera or a bad scene file fails before any frame is
// played (SequenceError, ConfigError). warn receives one line per frame the source skips.
std::unique_ptr<FrameSource> openFrameSource(const CaptureSettings& settings,
                                             std::function<void(const std::string&)> warn);

}  // namespace bmp::capture

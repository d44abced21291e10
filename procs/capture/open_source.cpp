#include "capture/open_source.hpp"

#include <algorithm>
#include <stdexcept>

#include "bmp/common/arg_parser.hpp"
#include "bmp/common/log.hpp"
#include "capture/camera_selection.hpp"
#include "capture/selected_source.hpp"
#include "capture/synthetic_config.hpp"
#include "capture/synthetic_source.hpp"
#include "capture/tum_source.hpp"

namespace bmp::capture {

namespace {

std::unique_ptr<FrameSource> openSynthetic(const CaptureSettings& settings) {
  const Config synthetic = Config::fromFile(settings.synthetic_config);
  SyntheticSceneConfig scene_config = syntheticSceneFromConfig(synthetic.section("synthetic"));
  synthetic.finish();
  // Frames past --end are never rendered; --start/--every are applied by index.
  const FrameSelection& selection = settings.selection;
  if (selection.end >= 0)
    scene_config.num_frames = static_cast<int>(std::min<int64_t>(scene_config.num_frames, selection.end));
  return std::make_unique<SelectedSource>(std::make_unique<SyntheticSource>(scene_config), selection);
}

std::unique_ptr<FrameSource> openTumFolder(const CaptureSettings& settings,
                                           std::function<void(const std::string&)> warn) {
  const std::string& dir = settings.dataset;
  // The folder first: a missing folder must be reported as such, not as an unknown camera.
  SequenceIndex index = indexSequence(dir, settings.max_association_difference_s);
  const SequenceCamera selected = selectCamera(dir, settings.camera, settings.cameras_dir);
  logSequenceFindings(index, selected);
  TumSourceOptions options;
  options.selection = settings.selection;
  options.verify = settings.verify;
  options.warn = std::move(warn);
  log::info(dir, ": ", index.frames.size(), " associated pairs from ", index.rgb_entries, " colour and ",
            index.depth_entries, " depth entries",
            index.groundtruth.empty() ? ", no ground truth" : ", with ground truth");
  return std::make_unique<TumSource>(std::move(index), selected.intrinsics, std::move(options));
}

}  // namespace

void logSequenceFindings(const SequenceIndex& index, const SequenceCamera& camera) {
  log::info("camera from ", camera.file, " (", camera.chosen_by, ")");
  if (!index.groundtruth_problem.empty())
    log::warn(index.groundtruth_problem, "; going on without ground truth");
  for (const auto& problem : index.list_problems) log::warn(problem);
}

std::unique_ptr<FrameSource> openFrameSource(const CaptureSettings& settings,
                                             std::function<void(const std::string&)> warn) {
  try {
    return settings.dataset.empty() ? openSynthetic(settings) : openTumFolder(settings, std::move(warn));
  } catch (const std::invalid_argument& e) {  // the frame selection (--start past the end): a usage error
    throw ArgError(std::string("bmp-capture: ") + e.what());
  }
}

}  // namespace bmp::capture

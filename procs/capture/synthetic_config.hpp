#pragma once
// The synthetic scene's tunables from a configuration section (key "synthetic" of config/synthetic.yaml).
#include "bmp/common/config.hpp"
#include "capture/synthetic_scene.hpp"

namespace bmp::capture {

// Reads every field of SyntheticSceneConfig by name; absent keys keep the struct's defaults. Throws
// ConfigError for a wrongly typed value or a list of the wrong length.
SyntheticSceneConfig syntheticSceneFromConfig(const bmp::Config& section);

}  // namespace bmp::capture

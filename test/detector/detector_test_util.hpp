#pragma once
// Building detectors from the repository's configuration and the shared models, for tests.
#include <string>

#include "bmp/common/config.hpp"
#include "detector/detector.hpp"
#include "shared_data.hpp"

namespace bmp::test {

inline Config repoDynamicClasses() {
  return Config::fromFile(sourceDir() + "/config/dynamic_classes.yaml");
}

inline detector::DetectorConfig presetConfig(const std::string& preset) {
  return detector::withModelPreset(detector::DetectorConfig{}, preset);
}

inline std::vector<std::string> cocoNames() {
  return detector::loadClassNames(sharedPath("models/coco.names"));
}

}  // namespace bmp::test

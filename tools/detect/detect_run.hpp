#pragma once
// bmp-detect's run: the detector over a list of images, each image's boxes on stdout and, with --out, an
// annotated PNG and JSON per image (or one detections.jsonl).
#include "bmp/common/arg_parser.hpp"

namespace bmp::detect_tools {

// Reads the options bmp-detect's main declares (--input, --out, --jsonl, --config, --dynamic-classes,
// --model, --conf, --threads, --limit); returns the exit code (0; an image the detector refuses is reported
// and skipped). Throws ArgError without --input, ConfigError for a bad configuration, std::runtime_error
// for a file it cannot read or write.
int runDetect(const ArgParser& args);

}  // namespace bmp::detect_tools

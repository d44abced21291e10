#include "tracker/tracker_options.hpp"

#include <stdexcept>

namespace bmp::tracker {

const char* toString(DynamicMode mode) {
  switch (mode) {
    case DynamicMode::kNone:
      return "none";
    case DynamicMode::kBoxes:
      return "boxes";
    case DynamicMode::kPaper:
      return "paper";
    case DynamicMode::kDepth:
      return "depth";
    case DynamicMode::kGeometric:
      return "geometric";
  }
  return "?";
}

DynamicMode parseDynamicMode(const std::string& name) {
  for (DynamicMode m : {DynamicMode::kNone, DynamicMode::kBoxes, DynamicMode::kPaper, DynamicMode::kDepth,
                        DynamicMode::kGeometric})
    if (name == toString(m)) return m;
  throw std::invalid_argument("must be none, boxes, paper, depth or geometric, got '" + name + "'");
}

}  // namespace bmp::tracker

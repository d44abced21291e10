#pragma once
// How likely an object class is to move, numbered as detection_t's LEVEL_* constants. The detector tags
// every box with one (config/dynamic_classes.yaml); the tracker's dynamic stage reads them.
#include <cstdint>

namespace bmp {

enum class DynamicLevel : int8_t {
  kLow = 0,     // does not move: monitor, table, refrigerator
  kMedium = 1,  // moved by people: chair, cup, book
  kHigh = 2,    // moves by itself: person, animals, vehicles
};

}  // namespace bmp

#include "detector/frame_slot.hpp"

#include <stdexcept>

namespace bmp::detector {

QueueMode parseQueueMode(const std::string& text) {
  if (text == "latest") return QueueMode::kLatest;
  if (text == "every") return QueueMode::kEvery;
  throw std::invalid_argument("mode must be 'latest' or 'every', got '" + text + "'");
}

const char* toString(QueueMode mode) {
  return mode == QueueMode::kLatest ? "latest" : "every";
}

}  // namespace bmp::detector

#include "capture/selected_source.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace bmp::capture {

SelectedSource::SelectedSource(std::unique_ptr<FrameSource> inner, FrameSelection selection)
    : inner_(std::move(inner)), selection_(selection) {
  if (selection_.every < 1) throw std::invalid_argument("frame selection: every must be >= 1");
  if (selection_.start < 0) throw std::invalid_argument("frame selection: start must be >= 0");
  if (inner_->size() >= 0 && selection_.start >= inner_->size())
    throw std::invalid_argument("--start " + std::to_string(selection_.start) + " is past the end of " +
                                inner_->name() + " (" + std::to_string(inner_->size()) + " frames)");
}

int64_t SelectedSource::size() const {
  return selectedCount(selection_, inner_->size());
}

std::optional<CapturedFrame> SelectedSource::next() {
  while (auto frame = inner_->next()) {
    if (selection_.end >= 0 && frame->index >= selection_.end) return std::nullopt;
    if (frame->index < selection_.start || (frame->index - selection_.start) % selection_.every != 0)
      continue;
    return frame;
  }
  return std::nullopt;
}

}  // namespace bmp::capture

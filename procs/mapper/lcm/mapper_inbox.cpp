#include "mapper/lcm/mapper_inbox.hpp"

#include <limits>

namespace bmp::mapper {

namespace {
// The count never binds before the bytes do (a pose update is the smallest message, 8 bytes and up).
constexpr std::size_t kQueueSlots = std::numeric_limits<uint32_t>::max();
}  // namespace

MapperInbox::MapperInbox(std::size_t max_bytes) : max_bytes_(max_bytes), queue_(kQueueSlots) {}

std::size_t MapperInbox::bytesOf(const Message& message) {
  if (const auto* kf = std::get_if<keyframe_t>(&message))
    return sizeof(keyframe_t) + kf->color.data.size() + kf->depth.data.size() + kf->dynamic_mask.data.size();
  const auto& poses = std::get<keyframe_poses_t>(message);
  return sizeof(keyframe_poses_t) + poses.ids.size() * sizeof(int64_t) +
         poses.T_world_cam.size() * sizeof(pose_t);
}

bool MapperInbox::offer(Message message) {
  const std::size_t bytes = bytesOf(message);
  // Only this thread adds bytes; the loop only takes them away, so the check errs on the full side.
  const std::size_t waiting = bytes_.load();
  if (waiting > 0 && waiting + bytes > max_bytes_) {
    ++refused_;
    return false;
  }
  bytes_ += bytes;
  if (queue_.tryPush({std::move(message), bytes})) return true;
  bytes_ -= bytes;  // closed
  ++refused_;
  return false;
}

std::optional<MapperInbox::Message> MapperInbox::popFor(std::chrono::milliseconds timeout) {
  return taken(queue_.popFor(timeout));
}

std::optional<MapperInbox::Message> MapperInbox::tryPop() {
  return taken(queue_.tryPop());
}

void MapperInbox::close() {
  queue_.close();
}

std::optional<MapperInbox::Message> MapperInbox::taken(std::optional<std::pair<Message, std::size_t>> item) {
  if (!item) return std::nullopt;
  bytes_ -= item->second;
  return std::move(item->first);
}

}  // namespace bmp::mapper

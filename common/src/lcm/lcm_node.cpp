#include "bmp/lcm/lcm_node.hpp"

#include <cstdlib>

#include "bmp/common/log.hpp"

namespace bmp {

std::string resolveLcmUrl(const std::string& command_line_url) {
  if (!command_line_url.empty()) return command_line_url;
  if (const char* env = std::getenv("LCM_DEFAULT_URL"); env != nullptr && *env != '\0') return env;
  return kDefaultLcmUrl;
}

LcmNode::LcmNode(const std::string& url, WarningSink warn) : url_(url), lcm_(url), warn_(std::move(warn)) {
  if (!lcm_.good()) throw LcmError("cannot open LCM at '" + url + "' (multicast route or URL wrong?)");
  if (!warn_) warn_ = [](const std::string& m) { log::warn(m); };
}

// subscribers_ is declared after lcm_, so the handlers go first and lcm::LCM's destructor then frees the
// subscriptions; nothing is dispatched in between.
LcmNode::~LcmNode() = default;

bool LcmNode::handle(int timeout_ms) {
  return lcm_.handleTimeout(timeout_ms) >= 0;
}

void LcmNode::subscribeRaw(const std::string& channel, RawHandler handler) {
  auto sub = std::make_unique<RawSubscriber>(std::move(handler));
  lcm::Subscription* s = lcm_.subscribe(channel, &RawSubscriber::onMessage, sub.get());
  s->setQueueCapacity(queue_capacity_);
  subscribers_.push_back(std::move(sub));
}

void LcmNode::reportMalformed(const std::string& channel, uint32_t size, const std::string& expected) {
  ++malformed_;
  warn_("malformed message on channel " + channel + " (" + std::to_string(size) + " bytes): not a " +
        expected + "; skipped (" + std::to_string(malformed_) + " so far)");
}

}  // namespace bmp

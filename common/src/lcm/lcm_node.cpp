#include "bmp/lcm/lcm_node.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <fstream>

#include "bmp/common/log.hpp"

namespace bmp {

std::string resolveLcmUrl(const std::string& command_line_url) {
  if (!command_line_url.empty()) return withReceiveBuffer(command_line_url);
  if (const char* env = std::getenv("LCM_DEFAULT_URL"); env != nullptr && *env != '\0')
    return withReceiveBuffer(env);
  return kDefaultLcmUrl;
}

std::string withReceiveBuffer(const std::string& url) {
  if (url.rfind("udpm://", 0) != 0 || url.find("recv_buf_size=") != std::string::npos) return url;
  const char last = url.back();
  const char* separator = url.find('?') == std::string::npos ? "?" : (last == '?' || last == '&' ? "" : "&");
  return url + separator + "recv_buf_size=" + std::to_string(kDefaultReceiveBufferBytes);
}

std::string receiveBufferWarning(const std::string& url, long rmem_max) {
  if (url.rfind("udpm://", 0) != 0) return "";
  const std::string key = "recv_buf_size=";
  const auto at = url.find(key);
  if (at == std::string::npos) return "";
  const long wanted = std::strtol(url.c_str() + at + key.size(), nullptr, 10);
  if (wanted <= 0 || rmem_max <= 0 || wanted <= rmem_max) return "";
  return "LCM asks for a " + std::to_string(wanted) + "-byte receive buffer but net.core.rmem_max is " +
         std::to_string(rmem_max) +
         ": the kernel gives less and large frames may be lost; raise it with "
         "'sudo sysctl -w net.core.rmem_max=" +
         std::to_string(wanted) + "' (tools/install-deps does)";
}

namespace {

long kernelRmemMax() {
  std::ifstream in("/proc/sys/net/core/rmem_max");
  long value = 0;
  return (in >> value) ? value : 0;
}

}  // namespace

LcmNode::LcmNode(const std::string& url, WarningSink warn) : url_(url), lcm_(url), warn_(std::move(warn)) {
  if (!lcm_.good())
    throw LcmError("cannot open LCM at '" + url +
                   "' (URL wrong, or no multicast route: see the README's troubleshooting section)");
  if (!warn_) warn_ = [](const std::string& m) { log::warn(m); };
  if (const std::string w = receiveBufferWarning(url, kernelRmemMax()); !w.empty()) warn_(w);
}

// subscribers_ is declared after lcm_, so the handlers go first and lcm::LCM's destructor then frees the
// subscriptions; nothing is dispatched in between.
LcmNode::~LcmNode() = default;

bool LcmNode::handle(int timeout_ms) {
  return lcm_.handleTimeout(timeout_ms) >= 0;
}

void LcmNode::subscribeRaw(const std::string& channel, RawHandler handler) {
  checkChannelName(channel);
  auto sub = std::make_unique<RawSubscriber>(this, std::move(handler));
  lcm_.subscribe(channel, &RawSubscriber::onMessage, sub.get())->setQueueCapacity(queue_capacity_);
  subscribers_.push_back(std::move(sub));
}

void checkChannelName(const std::string& channel) {
  const auto allowed = [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_' || c == '-' || c == '.' || c == '/' ||
           c == ':';
  };
  if (channel.empty() || channel.size() > LCM_MAX_CHANNEL_NAME_LENGTH ||
      !std::all_of(channel.begin(), channel.end(), allowed))
    throw LcmError("channel '" + log::printable(channel) + "': a channel name is 1 to " +
                   std::to_string(LCM_MAX_CHANNEL_NAME_LENGTH) +
                   " letters, digits and _ - . / : (LCM subscribes by regular expression)");
}

void LcmNode::guarded(const std::string& channel, uint32_t size, const std::function<void()>& call) {
  try {
    call();
  } catch (const std::exception& e) {
    reportMalformed(channel, size, std::string("message its handler could use (") + e.what() + ")");
  }
}

void LcmNode::reportMalformed(const std::string& channel, uint32_t size, const std::string& expected) {
  const int64_t total = ++malformed_;
  const std::optional<int64_t> left_out = warnings_.admit(channel);
  if (!left_out) return;
  std::string line = "malformed message on channel " + channel + " (" + std::to_string(size) +
                     " bytes): not a " + expected + "; skipped (" + std::to_string(total) + " so far";
  if (*left_out > 0) line += ", " + std::to_string(*left_out) + " more on " + channel + " not shown";
  warn_(line + ")");
}

}  // namespace bmp

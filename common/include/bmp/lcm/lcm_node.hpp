#pragma once
// One LCM connection with typed publish and subscribe. Subscriptions check each message's declared lengths
// against its bytes before decoding (wire_check.hpp), so a malformed or hostile message from another
// publisher is counted and reported (channel, size, reason) and can neither crash nor stall the process.
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <lcm/lcm-cpp.hpp>

#include "bmp/common/warning_throttle.hpp"
#include "bmp/lcm/wire_check.hpp"

namespace bmp {

// The URL every process uses unless told otherwise. The 4 MiB receive buffer keeps 640x480 frames from
// being dropped by the kernel.
inline constexpr const char* kDefaultLcmUrl = "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=4194304";
// LCM subscribes by regular expression and keeps channel names to 63 bytes: a channel name (from a
// configuration or the command line) must be 1-63 of letters, digits and _ - . / : , or this throws an
// LcmError naming it. Another name crashed the subscribing process (LCM made no subscription).
void checkChannelName(const std::string& channel);

inline constexpr long kDefaultReceiveBufferBytes = 4194304;  // the size in kDefaultLcmUrl (a test checks)

// --lcm-url if given, else $LCM_DEFAULT_URL, else kDefaultLcmUrl; then withReceiveBuffer.
std::string resolveLcmUrl(const std::string& command_line_url);

// A udpm URL that names no receive buffer gets LCM's, the kernel's small default, and full-size frames are
// then lost without a word: such a URL gets recv_buf_size=kDefaultReceiveBufferBytes. Other URLs, and udpm
// URLs that name a size, are returned as they are.
std::string withReceiveBuffer(const std::string& url);

// The kernel silently caps a socket's receive buffer at net.core.rmem_max: a udpm URL asking for more
// (recv_buf_size) then gets less, and large frames are lost under load. Returns the warning to give, or ""
// when the URL asks for nothing more than the kernel allows (or is not udpm).
std::string receiveBufferWarning(const std::string& url, long rmem_max);

class LcmError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct ReceivedInfo {
  std::string channel;
  int64_t recv_utime = 0;  // when LCM received it, microseconds
  std::size_t size = 0;    // encoded bytes
};

class LcmNode {
 public:
  using WarningSink = std::function<void(const std::string&)>;

  // Throws LcmError naming the URL when LCM cannot open it.
  explicit LcmNode(const std::string& url, WarningSink warn = nullptr);
  ~LcmNode();
  LcmNode(const LcmNode&) = delete;
  LcmNode& operator=(const LcmNode&) = delete;

  template <typename Msg>
  void publish(const std::string& channel, const Msg& msg) {
    if (lcm_.publish(channel, &msg) != 0) throw LcmError("publish on " + channel + " failed");
  }

  // Calls handler for each message on channel that decodes as Msg.
  template <typename Msg>
  void subscribe(const std::string& channel, std::function<void(const Msg&, const ReceivedInfo&)> handler) {
    checkChannelName(channel);
    auto sub = std::make_unique<Subscriber<Msg>>(this, std::move(handler));
    lcm_.subscribe(channel, &Subscriber<Msg>::onMessage, sub.get())->setQueueCapacity(queue_capacity_);
    subscribers_.push_back(std::move(sub));
  }

  // Raw bytes of every message on channel, for a channel that may carry more than one type; the handler
  // decodes, and reports what it cannot with reportMalformed().
  using RawHandler = std::function<void(const void* data, uint32_t size, const ReceivedInfo&)>;
  void subscribeRaw(const std::string& channel, RawHandler handler);
  // Counts a message that did not decode and warns, naming the channel, its size and what was expected.
  void reportMalformed(const std::string& channel, uint32_t size, const std::string& expected);

  // Waits up to timeout_ms for messages and dispatches them; returns false on an LCM error.
  bool handle(int timeout_ms);
  // Messages that did not decode, over all subscriptions.
  int64_t malformedCount() const { return malformed_.load(); }
  const std::string& url() const { return url_; }
  lcm::LCM& raw() { return lcm_; }
  // Messages LCM may queue per subscription before it drops the oldest (default 30).
  void setQueueCapacity(int capacity) { queue_capacity_ = capacity; }

 private:
  struct SubscriberBase {
    virtual ~SubscriberBase() = default;
  };
  template <typename Msg>
  struct Subscriber : SubscriberBase {
    Subscriber(LcmNode* node, std::function<void(const Msg&, const ReceivedInfo&)> fn)
        : node(node), handler(std::move(fn)) {}
    void onMessage(const lcm::ReceiveBuffer* rbuf, const std::string& channel) {
      Msg msg;
      std::string why;
      if (!wire::decode(msg, rbuf->data, rbuf->data_size, why)) {
        node->reportMalformed(channel, rbuf->data_size, std::string(Msg::getTypeName()) + " (" + why + ")");
        return;
      }
      node->guarded(channel, rbuf->data_size, [&] {
        handler(msg, ReceivedInfo{channel, rbuf->recv_utime, rbuf->data_size});
      });
    }
    LcmNode* node;
    std::function<void(const Msg&, const ReceivedInfo&)> handler;
  };
  struct RawSubscriber : SubscriberBase {
    RawSubscriber(LcmNode* node, RawHandler fn) : node(node), handler(std::move(fn)) {}
    void onMessage(const lcm::ReceiveBuffer* rbuf, const std::string& channel) {
      node->guarded(channel, rbuf->data_size, [&] {
        handler(rbuf->data, rbuf->data_size, ReceivedInfo{channel, rbuf->recv_utime, rbuf->data_size});
      });
    }
    LcmNode* node;
    RawHandler handler;
  };

  // Runs a handler; an exception it throws is reported and counted as malformed, never propagated through
  // LCM's C dispatch (which cannot unwind) and never ends the process.
  void guarded(const std::string& channel, uint32_t size, const std::function<void()>& call);

  std::string url_;
  lcm::LCM lcm_;
  WarningSink warn_;
  std::atomic<int64_t> malformed_{0};  // counted on whichever thread dispatches, read by the heartbeat
  WarningThrottle warnings_;           // per channel, so a flood of bad messages cannot flood the log
  int queue_capacity_ = 30;
  std::vector<std::unique_ptr<SubscriberBase>> subscribers_;
};

}  // namespace bmp

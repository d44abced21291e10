#pragma once
// Helpers for the tests that feed a running pipeline what a careless or hostile publisher would: messages
// built with the generated types and then patched, random bytes, truncated and oversized encodings; and a
// reader for the per-process figures of a run's summary.json.
#include <chrono>
#include <cstdint>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "bmp/lcm/lcm_node.hpp"

namespace bmp::test {

template <typename Msg>
std::vector<uint8_t> encoded(const Msg& msg) {
  std::vector<uint8_t> buf(static_cast<std::size_t>(msg.getEncodedSize()));
  msg.encode(buf.data(), 0, static_cast<int>(buf.size()));
  return buf;
}

// Overwrites the big-endian int32 at offset (LCM's byte order).
inline void putInt32(std::vector<uint8_t>& buf, std::size_t offset, int32_t v) {
  const auto u = static_cast<uint32_t>(v);
  for (int i = 0; i < 4; ++i) buf[offset + i] = static_cast<uint8_t>(u >> (24 - 8 * i));
}

inline std::vector<uint8_t> randomBytes(std::size_t n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> byte(0, 255);
  std::vector<uint8_t> out(n);
  for (auto& b : out) b = static_cast<uint8_t>(byte(rng));
  return out;
}

// Between hostile messages: a burst of megabytes would overflow the receivers' socket buffers and take real
// frames with it, which is the kernel's loss (counted as lost), not a decoding fault this test looks for.
inline void pace() {
  std::this_thread::sleep_for(std::chrono::milliseconds(30));
}

// Publishes random bytes, a truncated and an oversized (trailing bytes) encoding of good on channel: three
// messages no subscriber may decode.
template <typename Msg>
int publishJunk(LcmNode& lcm, const std::string& channel, const Msg& good, uint32_t seed) {
  const auto send = [&](const std::vector<uint8_t>& b) {
    lcm.raw().publish(channel, b.data(), static_cast<unsigned>(b.size()));
    pace();
  };
  send(randomBytes(200 + seed % 300, seed));
  std::vector<uint8_t> whole = encoded(good);
  send(std::vector<uint8_t>(whole.begin(), whole.begin() + static_cast<std::ptrdiff_t>(whole.size() / 2)));
  whole.resize(whole.size() + 65536, 0xab);
  send(whole);
  return 3;
}

// The number after "key": in the summary.json entry of process name, or -1.
inline long long processFigure(const std::string& json, const std::string& name, const std::string& key) {
  const std::size_t at = json.find("{\"name\": \"" + name + "\"");
  if (at == std::string::npos) return -1;
  const std::size_t end = json.find('}', at);
  const std::size_t k = json.find("\"" + key + "\": ", at);
  if (k == std::string::npos || k > end) return -1;
  return std::stoll(json.substr(k + key.size() + 4));
}

}  // namespace bmp::test

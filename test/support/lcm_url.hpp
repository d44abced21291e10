#pragma once
// A real multicast URL for tests that run processes over udpm://.
#include <unistd.h>

#include <stdexcept>
#include <string>

namespace bmp::test {

// A port of its own for this test process and slot: each process gets a block of 16 ports, so tests that
// ctest runs side by side (one process per test) never hear each other.
inline std::string uniqueLcmUrl(int slot) {
  if (slot < 0 || slot >= 16) throw std::invalid_argument("uniqueLcmUrl: slot must be in [0, 16)");
  const int port = 20000 + static_cast<int>(::getpid() % 2500) * 16 + slot;
  return "udpm://239.255.76.67:" + std::to_string(port) + "?ttl=0&recv_buf_size=4194304";
}

}  // namespace bmp::test

#include "bmp/common/log.hpp"

#include <chrono>
#include <cstdio>
#include <ctime>
#include <string>

namespace bmp::log {

std::string printable(const std::string& message) {
  std::string out;
  out.reserve(message.size());
  for (const char c : message) {
    const auto byte = static_cast<unsigned char>(c);
    if (c == '\n')
      out += "\n    ";
    else if ((byte < 0x20 && c != '\t') || byte == 0x7f)
      out += '?';
    else
      out += c;
  }
  return out;
}

void write(Level level, const std::string& message) {
  static constexpr const char* kTags[] = {"D", "I", "W", "E"};
  const auto now = std::chrono::system_clock::now();
  const std::time_t seconds = std::chrono::system_clock::to_time_t(now);
  const auto millis =
      std::chrono::duration_cast<std::chrono::milliseconds>(now.time_since_epoch()).count() % 1000;
  std::tm utc{};
  gmtime_r(&seconds, &utc);
  char stamp[32];
  std::strftime(stamp, sizeof(stamp), "%H:%M:%S", &utc);
  // One fprintf per line keeps lines from concurrent threads whole.
  std::fprintf(stderr, "[%s.%03d] [%s] %s\n", stamp, static_cast<int>(millis), kTags[static_cast<int>(level)],
               printable(message).c_str());
}

}  // namespace bmp::log

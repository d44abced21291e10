#pragma once
// Minimal logging to stderr: "[2026-11-22 02:10:11.123] [W] message". No state: the level filter is the
// caller's business, so libraries stay free of globals.
#include <sstream>
#include <string>

namespace bmp::log {

enum class Level { kDebug, kInfo, kWarn, kError };

// Writes one line (printable(message)) to stderr.
void write(Level level, const std::string& message);

// What goes into a log line is often another program's text (a label, a reason, a source name off LCM):
// control characters become '?' so none can rewrite the terminal, and a line break is indented so no text
// can pass for a line of our own ("[time] [E] ...").
std::string printable(const std::string& message);

template <typename... Args>
std::string concat(const Args&... args) {
  std::ostringstream out;
  (out << ... << args);
  return out.str();
}

template <typename... Args>
void info(const Args&... args) {
  write(Level::kInfo, concat(args...));
}
template <typename... Args>
void warn(const Args&... args) {
  write(Level::kWarn, concat(args...));
}
template <typename... Args>
void error(const Args&... args) {
  write(Level::kError, concat(args...));
}

}  // namespace bmp::log

#pragma once
// YAML configuration with validation. Every key read is recorded; finish() rejects keys nobody read, so a
// misspelt tunable is an error naming the file and key, never a silently ignored line.
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace YAML {
class Node;
}

namespace bmp {

class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class Config {
 public:
  // Throws ConfigError naming the file when it is missing or not valid YAML.
  static Config fromFile(const std::string& path);
  static Config fromString(const std::string& yaml, const std::string& origin);
  // An empty mapping: every get() returns its fallback.
  static Config empty(const std::string& origin);

  bool has(const std::string& key) const;
  // Value of key, or fallback when absent. A present value of the wrong type throws ConfigError.
  // Supported T: bool, int, int64_t, double, std::string, and std::vector of int, double, std::string.
  template <typename T>
  T get(const std::string& key, const T& fallback) const;
  template <typename T>
  T require(const std::string& key) const;
  // A nested mapping; absent means empty (all fallbacks apply).
  Config section(const std::string& key) const;
  // Keys of this mapping, in file order.
  std::vector<std::string> keys() const;

  // Accepts the whole subtree under key without reading it: for a tool that shares a file with a process
  // and does not use the process's sections. A misspelt key elsewhere is still an error.
  void ignore(const std::string& key) const;
  // Throws ConfigError listing every key in the file that was never read.
  void finish() const;
  // Records that a command-line option replaced key's value (read before with get()): effectiveValues()
  // then shows value_text and source instead of the file's value, which the process does not use.
  void overridden(const std::string& key, const std::string& value_text, const std::string& source) const;
  // "path.to.key = value" for every value read, with "(default)" where the fallback was used and the
  // option's name where one replaced it.
  std::vector<std::string> effectiveValues() const;
  const std::string& origin() const;
  std::string path(const std::string& key) const;  // full dotted key path, for messages
  // The one validation helper for every configuration: throws ConfigError "<file>: key 'a.b' <rule>"
  // unless ok, e.g. check(x > 0, "fx", "must be positive").
  void check(bool ok, const std::string& key, const std::string& rule) const;

 private:
  struct State;
  Config(std::shared_ptr<State> state, std::shared_ptr<YAML::Node> node, std::string prefix);
  std::shared_ptr<State> state_;
  std::shared_ptr<YAML::Node> node_;
  std::string prefix_;
};

}  // namespace bmp

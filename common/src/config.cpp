#include "bmp/common/config.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include <yaml-cpp/yaml.h>

namespace bmp {

struct Config::State {
  std::string origin;
  YAML::Node root;
  std::set<std::string> used;          // full paths of keys read
  std::set<std::string> ignored;       // full paths of subtrees accepted unread
  std::vector<std::string> effective;  // "path = value" in reading order
};

namespace {

template <typename T>
const char* typeName() {
  if constexpr (std::is_same_v<T, bool>) return "boolean";
  if constexpr (std::is_same_v<T, int> || std::is_same_v<T, int64_t>) return "integer";
  if constexpr (std::is_same_v<T, double>) return "number";
  if constexpr (std::is_same_v<T, std::string>) return "string";
  if constexpr (std::is_same_v<T, std::vector<int>>) return "list of integers";
  if constexpr (std::is_same_v<T, std::vector<double>>) return "list of numbers";
  if constexpr (std::is_same_v<T, std::vector<std::string>>) return "list of strings";
  return "value";
}

template <typename T>
std::string show(const T& value) {
  std::ostringstream out;
  if constexpr (std::is_same_v<T, bool>) {
    out << (value ? "true" : "false");
  } else if constexpr (std::is_same_v<T, std::vector<int>> || std::is_same_v<T, std::vector<double>> ||
                       std::is_same_v<T, std::vector<std::string>>) {
    out << "[";
    for (std::size_t i = 0; i < value.size(); ++i) out << (i ? ", " : "") << value[i];
    out << "]";
  } else {
    out << value;
  }
  return out.str();
}

template <typename T>
T convert(const YAML::Node& node, const std::string& origin, const std::string& path) {
  const auto fail = [&]() -> ConfigError {
    std::string got = node.IsScalar()     ? "'" + node.Scalar() + "'"
                      : node.IsSequence() ? "a list"
                      : node.IsNull()     ? "nothing (the key has no value)"
                                          : "a mapping";
    return ConfigError(origin + ": key '" + path + "' must be a " + typeName<T>() + ", got " + got);
  };
  if constexpr (std::is_same_v<T, std::vector<int>> || std::is_same_v<T, std::vector<double>> ||
                std::is_same_v<T, std::vector<std::string>>) {
    if (!node.IsSequence()) throw fail();
  } else {
    if (!node.IsScalar()) throw fail();
  }
  T value;
  try {
    value = node.as<T>();
  } catch (const YAML::Exception&) {
    throw fail();
  }
  // .inf and .nan are YAML numbers, but no setting's: a timeout of .inf waited forever without a word.
  bool finite = true;
  if constexpr (std::is_same_v<T, double>) finite = std::isfinite(value);
  if constexpr (std::is_same_v<T, std::vector<double>>)
    finite = std::all_of(value.begin(), value.end(), [](double v) { return std::isfinite(v); });
  if (!finite)
    throw ConfigError(
        origin + ": key '" + path + "' must hold finite numbers, got " +
        (node.IsScalar() ? "'" + node.Scalar() + "'" : std::string("a list with one that is not")));
  return value;
}

void collectUnused(const YAML::Node& node, const std::string& prefix, const std::set<std::string>& used,
                   const std::set<std::string>& ignored, std::vector<std::string>& unknown) {
  if (!node.IsMap()) return;
  for (const auto& kv : node) {
    const std::string path = prefix.empty() ? kv.first.Scalar() : prefix + "." + kv.first.Scalar();
    if (ignored.count(path)) continue;
    if (!used.count(path)) {
      unknown.push_back(path);
    } else if (kv.second.IsMap()) {
      collectUnused(kv.second, path, used, ignored, unknown);
    }
  }
}

// More nodes than any configuration of ours has, by far: YAML aliases can make a file of a few hundred
// bytes a tree of billions of nodes (each alias walked again), which took minutes to check.
constexpr long kMaxConfigNodes = 100000;

// Keys the reader would never find, refused naming file, line and key:
//   - a key written twice in one mapping: yaml-cpp keeps both and reads the first, so the value a user
//     edited last (lower down) would be ignored without a word;
//   - a key with a dot: keys are looked up section by section, so 'capture.speed: 100' at the top was
//     neither read nor reported unknown.
void refuseUnreadableKeys(const YAML::Node& node, const std::string& prefix, const std::string& origin,
                          long& nodes) {
  if (++nodes > kMaxConfigNodes)
    throw ConfigError(origin + ": more than " + std::to_string(kMaxConfigNodes) +
                      " values (YAML aliases nested in each other?)");
  if (node.IsSequence()) {
    for (const auto& item : node) refuseUnreadableKeys(item, prefix, origin, nodes);
    return;
  }
  if (!node.IsMap()) return;
  std::set<std::string> seen;
  for (const auto& kv : node) {
    const std::string& key = kv.first.Scalar();
    const std::string path = prefix.empty() ? key : prefix + "." + key;
    const std::string where =
        origin + ":" + std::to_string(kv.first.Mark().line + 1) + ": key '" + path + "'";
    if (!seen.insert(key).second)
      throw ConfigError(where + " is given twice (the first would be used and this one ignored)");
    if (key.find('.') != std::string::npos)
      throw ConfigError(where +
                        " has a dot in it: write sections as nested keys (e.g. 'capture: {speed: 2}')");
    refuseUnreadableKeys(kv.second, path, origin, nodes);
  }
}

}  // namespace

Config::Config(std::shared_ptr<State> state, std::shared_ptr<YAML::Node> node, std::string prefix)
    : state_(std::move(state)), node_(std::move(node)), prefix_(std::move(prefix)) {}

Config Config::fromFile(const std::string& path) {
  // A folder opens as a stream that reads nothing: every value would silently be its default.
  if (std::filesystem::is_directory(path)) throw ConfigError(path + ": a folder, not a configuration file");
  std::ifstream in(path);
  if (!in) throw ConfigError(path + ": cannot open configuration file");
  std::stringstream text;
  text << in.rdbuf();
  if (in.bad()) throw ConfigError(path + ": cannot read configuration file");
  return fromString(text.str(), path);
}

Config Config::fromString(const std::string& yaml, const std::string& origin) {
  auto state = std::make_shared<State>();
  state->origin = origin;
  try {
    state->root = YAML::Load(yaml);
  } catch (const YAML::Exception& e) {
    throw ConfigError(origin + ": not valid YAML: " + e.what());
  }
  if (state->root.IsNull()) state->root = YAML::Node(YAML::NodeType::Map);
  if (!state->root.IsMap()) throw ConfigError(origin + ": the top level must be a mapping of keys");
  long nodes = 0;
  refuseUnreadableKeys(state->root, "", origin, nodes);
  auto node = std::make_shared<YAML::Node>(state->root);
  return Config(state, node, "");
}

Config Config::empty(const std::string& origin) {
  return fromString("{}", origin);
}

std::string Config::path(const std::string& key) const {
  return prefix_.empty() ? key : prefix_ + "." + key;
}

const std::string& Config::origin() const {
  return state_->origin;
}

bool Config::has(const std::string& key) const {
  return node_->IsMap() && (*node_)[key].IsDefined();
}

template <typename T>
T Config::get(const std::string& key, const T& fallback) const {
  const std::string full = path(key);
  state_->used.insert(full);
  if (!has(key)) {
    state_->effective.push_back(full + " = " + show(fallback) + " (default)");
    return fallback;
  }
  T value = convert<T>((*node_)[key], state_->origin, full);
  state_->effective.push_back(full + " = " + show(value));
  return value;
}

template <typename T>
T Config::require(const std::string& key) const {
  if (!has(key)) throw ConfigError(state_->origin + ": required key '" + path(key) + "' is missing");
  return get<T>(key, T{});
}

Config Config::section(const std::string& key) const {
  const std::string full = path(key);
  state_->used.insert(full);
  if (!has(key)) return Config(state_, std::make_shared<YAML::Node>(YAML::NodeType::Map), full);
  YAML::Node child = (*node_)[key];
  if (!child.IsMap()) throw ConfigError(state_->origin + ": key '" + full + "' must be a mapping");
  return Config(state_, std::make_shared<YAML::Node>(child), full);
}

std::vector<std::string> Config::keys() const {
  std::vector<std::string> out;
  if (!node_->IsMap()) return out;
  for (const auto& kv : *node_) out.push_back(kv.first.Scalar());
  return out;
}

void Config::ignore(const std::string& key) const {
  state_->ignored.insert(path(key));
}

void Config::finish() const {
  std::vector<std::string> unknown;
  collectUnused(state_->root, "", state_->used, state_->ignored, unknown);
  if (unknown.empty()) return;
  std::string message = state_->origin + ": unknown key";
  message += unknown.size() > 1 ? "s " : " ";
  for (std::size_t i = 0; i < unknown.size(); ++i) message += (i ? ", '" : "'") + unknown[i] + "'";
  throw ConfigError(message);
}

void Config::overridden(const std::string& key, const std::string& value_text,
                        const std::string& source) const {
  const std::string full = path(key);
  state_->used.insert(full);
  const std::string line = full + " = " + value_text + " (" + source + ")";
  for (auto& entry : state_->effective) {
    if (entry.rfind(full + " = ", 0) == 0) {
      entry = line;
      return;
    }
  }
  state_->effective.push_back(line);
}

std::vector<std::string> Config::effectiveValues() const {
  return state_->effective;
}

template bool Config::get<bool>(const std::string&, const bool&) const;
template int Config::get<int>(const std::string&, const int&) const;
template int64_t Config::get<int64_t>(const std::string&, const int64_t&) const;
template double Config::get<double>(const std::string&, const double&) const;
template std::string Config::get<std::string>(const std::string&, const std::string&) const;
template std::vector<int> Config::get<std::vector<int>>(const std::string&, const std::vector<int>&) const;
template std::vector<double> Config::get<std::vector<double>>(const std::string&,
                                                              const std::vector<double>&) const;
template std::vector<std::string> Config::get<std::vector<std::string>>(
    const std::string&, const std::vector<std::string>&) const;
template bool Config::require<bool>(const std::string&) const;
template int Config::require<int>(const std::string&) const;
template int64_t Config::require<int64_t>(const std::string&) const;
template double Config::require<double>(const std::string&) const;
template std::string Config::require<std::string>(const std::string&) const;
template std::vector<int> Config::require<std::vector<int>>(const std::string&) const;
template std::vector<double> Config::require<std::vector<double>>(const std::string&) const;
template std::vector<std::string> Config::require<std::vector<std::string>>(const std::string&) const;

void Config::check(bool ok, const std::string& key, const std::string& rule) const {
  if (!ok) throw ConfigError(origin() + ": key '" + path(key) + "' " + rule);
}

}  // namespace bmp

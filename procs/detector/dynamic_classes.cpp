#include "detector/dynamic_classes.hpp"

#include <algorithm>
#include <stdexcept>

namespace bmp::detector {

const char* toString(DynamicLevel level) {
  switch (level) {
    case DynamicLevel::kLow:
      return "low";
    case DynamicLevel::kMedium:
      return "medium";
    case DynamicLevel::kHigh:
      return "high";
  }
  return "unknown";
}

DynamicClassTable DynamicClassTable::fromConfig(const Config& config,
                                                const std::vector<std::string>& class_names) {
  DynamicClassTable table;
  const std::pair<const char*, DynamicLevel> keys[] = {
      {"high", DynamicLevel::kHigh}, {"medium", DynamicLevel::kMedium}, {"low", DynamicLevel::kLow}};
  for (const auto& [key, level] : keys) {
    for (const auto& name : config.require<std::vector<std::string>>(key)) {
      if (std::find(class_names.begin(), class_names.end(), name) == class_names.end())
        throw ConfigError(config.origin() + ": key '" + config.path(key) + "' names unknown class '" + name +
                          "' (class names are those of coco.names, e.g. 'tvmonitor', 'cell phone')");
      const auto [it, inserted] = table.levels_.emplace(name, level);
      if (!inserted)
        throw ConfigError(config.origin() + ": class '" + name + "' is listed under both '" +
                          toString(it->second) + "' and '" + key + "'");
    }
  }
  std::vector<std::string> unmapped;
  for (const auto& name : class_names)
    if (!table.levels_.count(name)) unmapped.push_back(name);
  if (!unmapped.empty()) {
    std::string message = config.origin() + ": every class needs a dynamic level; not mapped: ";
    for (std::size_t i = 0; i < unmapped.size(); ++i) message += (i ? ", '" : "'") + unmapped[i] + "'";
    throw ConfigError(message);
  }
  config.finish();
  return table;
}

DynamicLevel DynamicClassTable::levelOf(const std::string& class_name) const {
  const auto it = levels_.find(class_name);
  if (it == levels_.end()) throw std::out_of_range("class '" + class_name + "' has no dynamic level");
  return it->second;
}

}  // namespace bmp::detector

#pragma once
// How likely each object class is to move (paper section 3.2): high moves by itself (people, animals),
// medium is moved by people (bags, cups, chairs), low does not move (monitors, tables, refrigerators).
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include "bmp/common/config.hpp"

namespace bmp::detector {

// Values match detection_t::LEVEL_* so the process can copy them into messages.
enum class DynamicLevel : int8_t { kLow = 0, kMedium = 1, kHigh = 2 };

const char* toString(DynamicLevel level);

class DynamicClassTable {
 public:
  // Reads keys high, medium and low, each a list of class names (config/dynamic_classes.yaml). Throws
  // ConfigError naming the file and key for a name not in class_names, a class listed twice, a class of
  // class_names left unmapped, or any other key.
  static DynamicClassTable fromConfig(const Config& config, const std::vector<std::string>& class_names);

  // Throws std::out_of_range naming the class when it is not in the table.
  DynamicLevel levelOf(const std::string& class_name) const;
  std::size_t size() const { return levels_.size(); }

 private:
  std::unordered_map<std::string, DynamicLevel> levels_;
};

}  // namespace bmp::detector

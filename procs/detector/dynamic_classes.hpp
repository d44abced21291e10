#pragma once
// How likely each object class is to move (paper section 3.2): high moves by itself (people, animals),
// medium is moved by people (bags, cups, chairs), low does not move (monitors, tables, refrigerators).
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include "bmp/common/config.hpp"
#include "bmp/common/dynamic_level.hpp"

namespace bmp::detector {

// One definition with the tracker's (values match detection_t::LEVEL_*).
using bmp::DynamicLevel;

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

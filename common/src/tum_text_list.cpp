#include "bmp/common/tum_text_list.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

namespace bmp {

bool normalizeTumLine(std::string& line) {
  std::replace(line.begin(), line.end(), ',', ' ');
  std::replace(line.begin(), line.end(), '\t', ' ');
  if (!line.empty() && line.back() == '\r') line.pop_back();
  const auto first = line.find_first_not_of(' ');
  return first != std::string::npos && line[first] != '#';
}

bool parseTumNumber(const std::string& text, double& value) {
  try {
    std::size_t used = 0;
    value = std::stod(text, &used);
    return used == text.size() && std::isfinite(value);
  } catch (const std::exception&) {  // not a number, or out of range
    return false;
  }
}

double TumTextRecord::number(std::size_t i) const {
  double value = 0.0;
  parseTumNumber(fields.at(i), value);
  return value;
}

namespace {

// Splits a normalised line into its record; false when it does not have the format's shape.
bool parseRecord(const std::string& line, const TumTextFormat& format, TumTextRecord& record) {
  std::istringstream in(line);
  std::string stamp;
  in >> stamp;
  if (!parseTumNumber(stamp, record.stamp)) return false;
  for (std::string field; in >> field;) record.fields.push_back(field);
  if (record.fields.size() != format.fields) return false;
  double unused = 0.0;
  if (format.numeric)
    for (const auto& field : record.fields)
      if (!parseTumNumber(field, unused)) return false;
  return true;
}

}  // namespace

std::vector<TumTextRecord> parseTumTextList(const std::string& text, const std::string& origin,
                                            const TumTextFormat& format) {
  std::vector<TumTextRecord> records;
  std::istringstream in(text);
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (!normalizeTumLine(line)) continue;
    TumTextRecord record;
    record.line = line_no;
    record.text = line;
    if (!parseRecord(line, format, record))
      throw TumTextError(origin + ":" + std::to_string(line_no) + ": expected '" + format.layout +
                         "', got '" + line + "'");
    records.push_back(std::move(record));
  }
  return records;
}

std::vector<TumTextRecord> readTumTextList(const std::string& path, const TumTextFormat& format) {
  std::ifstream in(path);
  if (!in) throw TumTextError(path + ": cannot open " + format.kind);
  std::stringstream text;
  text << in.rdbuf();
  return parseTumTextList(text.str(), path, format);
}

}  // namespace bmp

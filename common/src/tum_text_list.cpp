#include "bmp/common/tum_text_list.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string_view>

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

std::vector<TumTextRecord> parseTumTextList(const std::string& text_in, const std::string& origin,
                                            const TumTextFormat& format, std::string* cut_last_line) {
  // Editors on Windows start UTF-8 files with a byte-order mark; it would make the first stamp unreadable.
  constexpr std::string_view kByteOrderMark = "\xEF\xBB\xBF";
  const std::string_view text = std::string_view(text_in).substr(
      std::string_view(text_in).substr(0, kByteOrderMark.size()) == kByteOrderMark ? kByteOrderMark.size()
                                                                                   : 0);
  if (cut_last_line != nullptr) cut_last_line->clear();
  std::vector<TumTextRecord> records;
  std::istringstream in{std::string(text)};
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (!normalizeTumLine(line)) continue;
    TumTextRecord record;
    record.line = line_no;
    record.text = line;
    if (!parseRecord(line, format, record)) {
      const std::string where = origin + ":" + std::to_string(line_no);
      if (cut_last_line != nullptr && in.eof() && !text.empty() && text.back() != '\n') {
        *cut_last_line = where + ": the last line, '" + line +
                         "', has no end of line and is not a whole record (the file was cut off while "
                         "written); left out";
        break;
      }
      throw TumTextError(where + ": expected '" + format.layout + "', got '" + line + "'");
    }
    records.push_back(std::move(record));
  }
  return records;
}

std::vector<TumTextRecord> readTumTextList(const std::string& path, const TumTextFormat& format,
                                           std::string* cut_last_line) {
  std::ifstream in(path);
  if (!in) throw TumTextError(path + ": cannot open " + format.kind);
  std::stringstream text;
  text << in.rdbuf();
  return parseTumTextList(text.str(), path, format, cut_last_line);
}

}  // namespace bmp

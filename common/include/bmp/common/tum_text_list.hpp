#pragma once
// The line format every TUM RGB-D text file shares (groundtruth.txt and trajectories, rgb.txt, depth.txt):
// one record per line starting with a timestamp, '#' comments and blank lines skipped, and fields separated
// by spaces, tabs or commas, as the TUM scripts read them. One parser for all, so they accept the same files.
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace bmp {

class TumTextError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Normalises one line as the TUM scripts read it: commas and tabs become spaces, a trailing CR goes.
// Returns false for a blank line or a '#' comment.
bool normalizeTumLine(std::string& line);

// A whole, finite decimal number: what a stamp or a numeric field must be.
bool parseTumNumber(const std::string& text, double& value);

struct TumTextFormat {
  std::string kind;        // e.g. "list file", for "cannot open list file"
  std::string layout;      // e.g. "timestamp filename", for "expected 'timestamp filename'"
  std::size_t fields = 1;  // after the timestamp, exactly
  bool numeric = false;    // every field a finite number as well
};

struct TumTextRecord {
  int line = 0;                     // 1-based line number in the file
  std::string text;                 // the line as normalised, for messages
  double stamp = 0.0;               // seconds
  std::vector<std::string> fields;  // after the stamp
  // Field i as a number; valid for a numeric format (checked while parsing).
  double number(std::size_t i) const;
};

// Every record of the text, in file order; a UTF-8 byte-order mark before the first line is ignored. Throws
// TumTextError "<origin>:<line>: expected '<layout>', got '<line>'" for a line whose stamp is not a number or
// whose field count (or numbers) is wrong. With cut_last_line given, a malformed last line that has no end of
// line (a recorder killed while writing it) is left out instead, and described there ("" when none was).
std::vector<TumTextRecord> parseTumTextList(const std::string& text, const std::string& origin,
                                            const TumTextFormat& format,
                                            std::string* cut_last_line = nullptr);
// The same from a file; throws TumTextError "<path>: cannot open <kind>" when it cannot be read.
std::vector<TumTextRecord> readTumTextList(const std::string& path, const TumTextFormat& format,
                                           std::string* cut_last_line = nullptr);

}  // namespace bmp

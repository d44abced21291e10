#pragma once
// Command-line options: --name VALUE, --name=VALUE and --flag, with generated --help text.
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace bmp {

class ArgError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class ArgParser {
 public:
  ArgParser(std::string program, std::string summary);

  void addFlag(const std::string& name, const std::string& help);
  void addOption(const std::string& name, const std::string& metavar, const std::string& help,
                 const std::string& default_value = "");
  // Free text appended to --help (examples, outputs).
  void addEpilog(const std::string& text) { epilog_ += text; }

  // Returns false when --help was asked for (the caller prints help() and exits 0).
  // Throws ArgError for an unknown option, a missing value or a stray argument.
  bool parse(int argc, const char* const* argv);

  bool flag(const std::string& name) const;
  bool given(const std::string& name) const;
  std::string value(const std::string& name) const;
  double number(const std::string& name) const;  // finite; throws ArgError naming the option
  // Any number strtod reads, inf and nan too (for a range check that names the range in its error).
  double anyNumber(const std::string& name) const;
  long long integer(const std::string& name) const;
  // The items of a comma-separated value ("a,b,,c" -> a, b, c); empty when the option is empty.
  std::vector<std::string> list(const std::string& name) const;
  std::string help() const;
  const std::string& program() const { return program_; }

 private:
  struct Option {
    std::string metavar;  // empty for a flag
    std::string help;
    std::string default_value;
    bool given = false;
    std::string value;
  };
  const Option& find(const std::string& name) const;
  std::string program_;
  std::string summary_;
  std::string epilog_;
  std::vector<std::string> order_;
  std::map<std::string, Option> options_;
};

}  // namespace bmp

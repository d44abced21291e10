#include "bmp/common/arg_parser.hpp"

#include <cmath>

#include <cstdlib>
#include <sstream>

namespace bmp {

ArgParser::ArgParser(std::string program, std::string summary)
    : program_(std::move(program)), summary_(std::move(summary)) {
  addFlag("help", "print this help and exit");
}

void ArgParser::addFlag(const std::string& name, const std::string& help) {
  if (!options_.count(name)) order_.push_back(name);
  options_[name] = Option{"", help, "", false, ""};
}

void ArgParser::addOption(const std::string& name, const std::string& metavar, const std::string& help,
                          const std::string& default_value) {
  if (!options_.count(name)) order_.push_back(name);
  options_[name] = Option{metavar, help, default_value, false, ""};
}

bool ArgParser::parse(int argc, const char* const* argv) {
  for (int i = 1; i < argc; ++i) {
    std::string arg = argv[i];
    if (arg.rfind("--", 0) != 0)
      throw ArgError(program_ + ": unexpected argument '" + arg + "' (see --help)");
    std::string name = arg.substr(2);
    std::string inline_value;
    bool has_inline = false;
    if (const auto eq = name.find('='); eq != std::string::npos) {
      inline_value = name.substr(eq + 1);
      name = name.substr(0, eq);
      has_inline = true;
    }
    auto it = options_.find(name);
    if (it == options_.end()) throw ArgError(program_ + ": unknown option '--" + name + "' (see --help)");
    Option& opt = it->second;
    opt.given = true;
    if (opt.metavar.empty()) {
      if (has_inline) throw ArgError(program_ + ": option '--" + name + "' takes no value");
      continue;
    }
    if (has_inline) {
      opt.value = inline_value;
    } else {
      if (i + 1 >= argc) throw ArgError(program_ + ": option '--" + name + "' needs a value " + opt.metavar);
      // `--dataset --out x` took "--out" as the folder and went on without the option the user gave; a
      // value that really starts with an option's name can still be given as --dataset=VALUE.
      const std::string next = argv[i + 1];
      if (next.rfind("--", 0) == 0 && options_.count(next.substr(2, next.find('=') - 2)) != 0)
        throw ArgError(program_ + ": option '--" + name + "' needs a value " + opt.metavar + " before '" +
                       next + "'");
      opt.value = argv[++i];
    }
  }
  return !flag("help");
}

const ArgParser::Option& ArgParser::find(const std::string& name) const {
  auto it = options_.find(name);
  if (it == options_.end()) throw ArgError(program_ + ": internal: option '" + name + "' was never declared");
  return it->second;
}

bool ArgParser::flag(const std::string& name) const {
  return find(name).given;
}
bool ArgParser::given(const std::string& name) const {
  return find(name).given;
}

std::string ArgParser::value(const std::string& name) const {
  const Option& opt = find(name);
  return opt.given ? opt.value : opt.default_value;
}

double ArgParser::anyNumber(const std::string& name) const {
  const std::string text = value(name);
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0')
    throw ArgError(program_ + ": --" + name + " must be a number, got '" + text + "'");
  return v;
}

double ArgParser::number(const std::string& name) const {
  const double v = anyNumber(name);
  // inf and nan are numbers to strtod, but no option's: --speed inf played as fast as it could.
  if (!std::isfinite(v))
    throw ArgError(program_ + ": --" + name + " must be a finite number, got '" + value(name) + "'");
  return v;
}

std::vector<std::string> ArgParser::list(const std::string& name) const {
  std::vector<std::string> items;
  std::stringstream text(value(name));
  for (std::string item; std::getline(text, item, ',');)
    if (!item.empty()) items.push_back(item);
  return items;
}

long long ArgParser::integer(const std::string& name) const {
  const std::string text = value(name);
  char* end = nullptr;
  const long long v = std::strtoll(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0')
    throw ArgError(program_ + ": --" + name + " must be an integer, got '" + text + "'");
  return v;
}

std::string ArgParser::help() const {
  std::ostringstream out;
  out << "Usage: " << program_ << " [options]\n\n" << summary_ << "\n\nOptions:\n";
  for (const auto& name : order_) {
    const Option& opt = options_.at(name);
    std::string left = "  --" + name + (opt.metavar.empty() ? "" : " " + opt.metavar);
    if (left.size() < 30)
      left.resize(30, ' ');
    else
      left += "\n" + std::string(30, ' ');
    out << left << opt.help;
    if (!opt.default_value.empty()) out << " (default: " << opt.default_value << ")";
    out << "\n";
  }
  if (!epilog_.empty()) out << "\n" << epilog_ << (epilog_.back() == '\n' ? "" : "\n");
  return out.str();
}

}  // namespace bmp

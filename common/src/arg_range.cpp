#include "bmp/common/arg_range.hpp"

#include <cmath>
#include <limits>
#include <sstream>

namespace bmp {

namespace {

[[noreturn]] void outOfRange(const ArgParser& args, const std::string& name, const std::string& range) {
  throw ArgError(args.program() + ": --" + name + " must be " + range + ", got '" + args.value(name) + "'");
}

template <typename T>
std::string rangeText(T min, T max) {
  std::ostringstream text;
  const bool unbounded = max == std::numeric_limits<T>::max() ||
                         (std::numeric_limits<T>::has_infinity && max == std::numeric_limits<T>::infinity());
  if (unbounded)
    text << "of at least " << min;
  else
    text << "from " << min << " to " << max;
  return text.str();
}

}  // namespace

double numberIn(const ArgParser& args, const std::string& name, double min, double max) {
  const double v = args.anyNumber(name);
  // NaN fails both comparisons, so it is refused with the rest.
  if (!(std::isfinite(v) && v >= min && v <= max)) outOfRange(args, name, "a number " + rangeText(min, max));
  return v;
}

double positiveNumber(const ArgParser& args, const std::string& name) {
  const double v = args.anyNumber(name);
  if (!(std::isfinite(v) && v > 0)) outOfRange(args, name, "a number above 0");
  return v;
}

long long integerIn(const ArgParser& args, const std::string& name, long long min, long long max) {
  const long long v = args.integer(name);
  if (v < min || v > max) outOfRange(args, name, "an integer " + rangeText(min, max));
  return v;
}

}  // namespace bmp

#pragma once
// Option values checked against the range they make sense in. A value outside it is a usage error
// (ArgError) naming the option, the range and the value given: --frames -3 must not quietly mean "every
// frame", nor --robot-radius nan "no robot".
#include <string>

#include "bmp/common/arg_parser.hpp"

namespace bmp {

// A finite number in [min, max] (max may be infinity: no upper bound).
double numberIn(const ArgParser& args, const std::string& name, double min, double max);
// A finite number above zero: a scale, a distance, an interval.
double positiveNumber(const ArgParser& args, const std::string& name);
// An integer in [min, max].
long long integerIn(const ArgParser& args, const std::string& name, long long min, long long max);

}  // namespace bmp

#pragma once
// bmp-eval's command: its options, their up-front checks and the evaluation they ask for (ATE, RPE, the
// text report, and the optional JSON, aligned estimate and plots).
#include "bmp/common/arg_parser.hpp"

namespace bmp::eval {

// Exit status of an evaluation that failed on its input (unreadable or malformed file, no overlap).
constexpr int kBadInput = 2;

// The parser with every option of bmp-eval and its --help text.
ArgParser makeEvalParser();

// Throws (ArgError, or std::invalid_argument for --rpe-unit) when the parsed command line lacks --gt or
// --est or an option value does not parse, so a typo is a command-line error, not bad input.
void checkEvalArgs(const ArgParser& args);

// Evaluates, prints the text report on stdout and writes what the options ask for; returns 0. Throws
// EvalError (or another std::exception) for bad input.
int runEval(const ArgParser& args);

}  // namespace bmp::eval

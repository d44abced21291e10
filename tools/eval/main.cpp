// bmp-eval: ATE and RPE of an estimated trajectory against ground truth, with the numbers of the TUM RGB-D
// benchmark's evaluate_ate.py and evaluate_rpe.py --fixed_delta, plus optional JSON, plots and the aligned
// estimate.
#include <exception>
#include <iostream>

#include "eval/eval_command.hpp"

int main(int argc, char** argv) {
  bmp::ArgParser args = bmp::eval::makeEvalParser();
  try {
    if (!args.parse(argc, argv)) {
      std::cout << args.help();
      return 0;
    }
    bmp::eval::checkEvalArgs(args);
  } catch (const std::exception& e) {
    std::cerr << e.what() << "\n";
    return 1;
  }
  try {
    return bmp::eval::runEval(args);
  } catch (const std::exception& e) {  // EvalError and the rest: the input could not be evaluated
    std::cerr << "bmp-eval: error: " << e.what() << "\n";
    return bmp::eval::kBadInput;
  }
}

#pragma once
// The one error type of bmp_eval: bad input (unreadable file, no overlapping stamps). The message names the
// file so that bmp-eval can print it as a one-line diagnostic.
#include <stdexcept>

namespace bmp::eval {

class EvalError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace bmp::eval

#pragma once
// Runs one of the project's commands to its end, for tests of the tools as a user meets them.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "bmp/common/child_process.hpp"
#include "shared_data.hpp"

namespace bmp::test {

// A command run to its end (or killed after timeout_s): its exit status (-1: timed out) and its output
// (stdout and stderr together).
struct Outcome {
  int status = -1;
  std::string output;
};

// name: the scratch folder its output goes to (one per test case: see scratchDir).
inline Outcome runCommand(const std::string& name, std::vector<std::string> argv, double timeout_s = 60) {
  const std::filesystem::path log = scratchDir("cmd_" + name) / "out.log";
  ChildProcess child(std::move(argv), ChildProcess::Output::kFile, log.string());
  Outcome o;
  o.status = child.wait(timeout_s).value_or(-1);
  o.output = readText(log.string());
  return o;
}

}  // namespace bmp::test

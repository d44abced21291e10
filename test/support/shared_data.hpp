#pragma once
// Paths to ../shared (read in place, never copied) and to the repository, for tests.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace bmp::test {

inline std::string sharedDir() {
  if (const char* env = std::getenv("BMP_SHARED"); env != nullptr && *env != '\0') return env;
  return BMP_SHARED_DIR_DEFAULT;
}
inline std::string sharedPath(const std::string& relative) {
  return sharedDir() + "/" + relative;
}
inline std::string bonnDir() {
  return sharedPath("data/rgbd_bonn_crowd");
}
inline std::string sourceDir() {
  return BMP_SOURCE_DIR;
}
inline std::string binaryDir() {
  return BMP_BINARY_DIR;
}
inline std::string binPath(const std::string& name) {
  return std::string(BMP_BINARY_DIR) + "/bin/" + name;
}

// A fresh empty directory under the build tree's test scratch area, of its own for the running test: ctest
// runs every test case as a process of its own, two at a time, so two cases asking for the same name must
// not wipe each other's folder.
inline std::filesystem::path scratchDir(const std::string& name) {
  std::string test = "outside-a-test";
  if (const auto* info = ::testing::UnitTest::GetInstance()->current_test_info())
    test = std::string(info->test_suite_name()) + "." + info->name();
  for (char& c : test)
    if (c == '/') c = '_';
  const auto dir = std::filesystem::path(BMP_BINARY_DIR) / "test-scratch" / test / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// A tab-separated file's rows (lines starting with '#' left out), each split at tabs: e.g. bmp-tracker's
// frame log.
inline std::vector<std::vector<std::string>> readTsvRows(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::vector<std::string>> rows;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::stringstream fields(line);
    rows.emplace_back();
    for (std::string f; std::getline(fields, f, '\t');) rows.back().push_back(f);
  }
  return rows;
}

// A whole text file ("" when it cannot be read), e.g. a process's log.
inline std::string readText(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The first line of a text file ("" when it cannot be read).
inline std::string readFirstLine(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  return line;
}

}  // namespace bmp::test

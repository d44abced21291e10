#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "launcher/run_folder.hpp"
#include "shared_data.hpp"

namespace bmp::launcher {
namespace {

void writeText(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path) << text;
}

std::string readText(const std::filesystem::path& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// A second run into the same --out folder, of a sequence without ground truth, used to be evaluated against
// the first run's groundtruth.txt (a failed run, or a wrong ATE where the stamps overlapped) and left its
// eval.json and plots beside the new trajectory. They are set aside as .prev; other files stay.
TEST(RunFolder, AnEarlierRunsResultsAreSetAsideAsPrev) {
  namespace fs = std::filesystem;
  const fs::path dir = test::scratchDir("run_folder_earlier");
  writeText(dir / "groundtruth.txt", "1 0 0 0 0 0 0 1\n");
  writeText(dir / "eval.json", "{\"ate\": 1}");
  fs::create_directories(dir / "plots");
  writeText(dir / "plots" / "trajectory.png", "png");
  writeText(dir / "eval.json.prev", "older");
  writeText(dir / "trajectory.txt", "kept by its writer");

  const auto moved = setAsideEarlierResults(dir.string());
  EXPECT_EQ(moved, (std::vector<std::string>{"groundtruth.txt", "eval.json", "plots"}));
  EXPECT_FALSE(fs::exists(dir / "groundtruth.txt"));
  EXPECT_FALSE(fs::exists(dir / "eval.json"));
  EXPECT_FALSE(fs::exists(dir / "plots"));
  EXPECT_EQ(readText(dir / "groundtruth.txt.prev"), "1 0 0 0 0 0 0 1\n");
  EXPECT_EQ(readText(dir / "eval.json.prev"), "{\"ate\": 1}");  // the older .prev replaced
  EXPECT_TRUE(fs::exists(dir / "plots.prev" / "trajectory.png"));
  EXPECT_EQ(readText(dir / "trajectory.txt"), "kept by its writer");

  EXPECT_TRUE(setAsideEarlierResults(dir.string()).empty());  // nothing left to set aside
}

}  // namespace
}  // namespace bmp::launcher

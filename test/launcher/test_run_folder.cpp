#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "bmp/common/arg_parser.hpp"
#include "launcher/run_folder.hpp"
#include "shared_data.hpp"

namespace bmp::launcher {
namespace {

namespace fs = std::filesystem;

void writeText(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path) << text;
}

// A second run into the same --out used to keep only some files as .prev and overwrite the rest (map/,
// frames.tsv, logs/), so after a good run and two failed ones the good map was gone, and new files sat
// beside old ones. Now the earlier run moves as a whole into previous/, replacing the one kept before.
TEST(RunFolder, AnEarlierRunMovesWhollyIntoPrevious) {
  const fs::path dir = test::scratchDir("run_folder_earlier");
  writeText(dir / "logs" / "bmp-tracker.log", "second run");
  writeText(dir / "trajectory.txt", "second run's poses");
  writeText(dir / "map" / "map.pcd", "second run's map");
  writeText(dir / "frames.tsv", "second run's frames");
  writeText(dir / "eval.json", "{\"ate\": 1}");
  writeText(dir / "previous" / "trajectory.txt", "first run's poses");

  EXPECT_TRUE(setAsideEarlierRun(dir.string()));
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);  // previous/ alone
  EXPECT_EQ(test::readText((dir / "previous" / "trajectory.txt").string()), "second run's poses");
  EXPECT_EQ(test::readText((dir / "previous" / "map" / "map.pcd").string()), "second run's map");
  EXPECT_EQ(test::readText((dir / "previous" / "frames.tsv").string()), "second run's frames");
  EXPECT_TRUE(fs::exists(dir / "previous" / "logs" / "bmp-tracker.log"));
  EXPECT_TRUE(fs::exists(dir / "previous" / "eval.json"));
  EXPECT_FALSE(fs::exists(dir / "previous" / "previous"));  // one earlier run is kept, not a chain
}

TEST(RunFolder, NewOrEmptyFolderHasNothingToMove) {
  const fs::path dir = test::scratchDir("run_folder_new");
  EXPECT_FALSE(setAsideEarlierRun((dir / "missing").string()));
  EXPECT_FALSE(setAsideEarlierRun(dir.string()));
  EXPECT_FALSE(fs::exists(dir / "previous"));
}

// A folder no run wrote (--out ~ by mistake) is refused as a usage error and left untouched.
TEST(RunFolder, FolderThatIsNotARunsIsRefused) {
  const fs::path dir = test::scratchDir("run_folder_foreign");
  writeText(dir / "notes.txt", "mine");
  EXPECT_THROW(setAsideEarlierRun(dir.string()), ArgError);
  EXPECT_EQ(test::readText((dir / "notes.txt").string()), "mine");
  EXPECT_FALSE(fs::exists(dir / "previous"));
  EXPECT_THROW(setAsideEarlierRun((dir / "notes.txt").string()), ArgError);  // a file, not a folder
}

}  // namespace
}  // namespace bmp::launcher

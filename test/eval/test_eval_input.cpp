#include <gtest/gtest.h>

#include "eval/eval_error.hpp"
#include "eval/eval_input.hpp"
#include "eval_test_util.hpp"
#include "shared_data.hpp"

namespace bmp::eval {

namespace {
std::string errorOf(const std::string& path) {
  try {
    loadTrajectory(path);
  } catch (const EvalError& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(evalInput, MalformedLineErrorNamesFileAndLine) {
  const std::string path = (bmp::test::scratchDir("eval_input_malformed") / "bad.txt").string();
  test::writeText(path, "# comment\n1.0 0 0 0 0 0 0 1\n2.0 0 0 zero 0 0 0 1\n");
  const std::string message = errorOf(path);
  EXPECT_NE(message.find(path + ":3"), std::string::npos) << message;
}

TEST(evalInput, ShortLineAndMissingFileAndEmptyFile) {
  const auto dir = bmp::test::scratchDir("eval_input_other");
  const std::string short_line = (dir / "short.txt").string();
  test::writeText(short_line, "1.0 0 0 0 0 0 0 1\n\n2.0 0 0 0 0 0 1\n");
  EXPECT_NE(errorOf(short_line).find(short_line + ":3"), std::string::npos) << errorOf(short_line);

  const std::string missing = (dir / "missing.txt").string();
  EXPECT_NE(errorOf(missing).find(missing), std::string::npos) << errorOf(missing);

  const std::string empty = (dir / "empty.txt").string();
  test::writeText(empty, "# only a comment\n");
  EXPECT_NE(errorOf(empty).find(empty + ": no poses"), std::string::npos) << errorOf(empty);
}

// Commas and tabs separate fields; a repeated stamp keeps its last line, as the scripts' dict does.
TEST(evalInput, SeparatorsAndRepeatedStamps) {
  const std::string path = (bmp::test::scratchDir("eval_input_dups") / "dups.txt").string();
  test::writeText(path, "2.0,5,0,0,0,0,0,1\n1.0\t1\t0\t0\t0\t0\t0\t1\n2.0 7 0 0 0 0 0 1\n");
  const Trajectory t = loadTrajectory(path);
  ASSERT_EQ(t.size(), 2u);
  EXPECT_DOUBLE_EQ(t[0].stamp, 1.0);
  EXPECT_DOUBLE_EQ(t[1].T_world_cam.translation().x(), 7.0);
}

TEST(evalInput, ReadsTheBonnGroundTruth) {
  const Trajectory t = loadTrajectory(bmp::test::bonnDir() + "/groundtruth.txt");
  EXPECT_GT(t.size(), 900u);
}

}  // namespace bmp::eval

// The one parser of TUM text files: separators, comments, field counts, numbers, and errors naming file and
// line.
#include <gtest/gtest.h>

#include <fstream>

#include "bmp/common/tum_text_list.hpp"
#include "shared_data.hpp"

namespace bmp {
namespace {

const TumTextFormat kList{"list file", "timestamp filename", 1, false};
const TumTextFormat kPoses{"trajectory file", "timestamp tx ty tz qx qy qz qw", 7, true};

TEST(TumTextList, SkipsCommentsAndBlankLinesAndAcceptsEverySeparator) {
  const auto records = parseTumTextList(
      "# colour images\n\n   # indented comment\n1.5 rgb/1.png\r\n2.25\trgb/2.png\n3,rgb/3.png\n  4 "
      "rgb/4.png  \n",
      "rgb.txt", kList);
  ASSERT_EQ(records.size(), 4u);
  EXPECT_EQ(records[0].line, 4);
  EXPECT_DOUBLE_EQ(records[0].stamp, 1.5);
  EXPECT_EQ(records[0].fields, std::vector<std::string>{"rgb/1.png"});
  EXPECT_DOUBLE_EQ(records[1].stamp, 2.25);
  EXPECT_EQ(records[2].fields[0], "rgb/3.png");
  EXPECT_EQ(records[3].line, 7);
  EXPECT_EQ(records[3].fields[0], "rgb/4.png");
}

TEST(TumTextList, NumericFieldsAreChecked) {
  const auto records = parseTumTextList("1 0.5 -2 3e-1 0 0 0 1\n", "t.txt", kPoses);
  ASSERT_EQ(records.size(), 1u);
  EXPECT_DOUBLE_EQ(records[0].number(1), -2.0);
  EXPECT_DOUBLE_EQ(records[0].number(2), 0.3);
  EXPECT_THROW(parseTumTextList("1 0 0 x 0 0 0 1\n", "t.txt", kPoses), TumTextError);
  EXPECT_THROW(parseTumTextList("1 0 0 nan 0 0 0 1\n", "t.txt", kPoses), TumTextError);
  // A file name that looks like a number is still a file name in a non-numeric format.
  EXPECT_EQ(parseTumTextList("1 2\n", "t.txt", kList)[0].fields[0], "2");
}

TEST(TumTextList, MalformedLinesNameFileAndLine) {
  const struct {
    const char* text;
    const char* where;
  } cases[] = {
      {"# header\n1.0 rgb/1.png\nnot-a-stamp rgb/2.png\n", "rgb.txt:3"},
      {"1.0\n", "rgb.txt:1"},              // too few fields
      {"1.0 a.png b.png\n", "rgb.txt:1"},  // too many
      {"\n\n1.0x a.png\n", "rgb.txt:3"},   // trailing garbage on the stamp
      {"1e999 a.png\n", "rgb.txt:1"},      // not finite
  };
  for (const auto& c : cases) {
    try {
      parseTumTextList(c.text, "rgb.txt", kList);
      ADD_FAILURE() << c.text;
    } catch (const TumTextError& e) {
      const std::string message = e.what();
      EXPECT_EQ(message.rfind(std::string(c.where) + ": expected 'timestamp filename', got '", 0), 0u)
          << message;
    }
  }
}

TEST(TumTextList, AByteOrderMarkIsNotPartOfTheFirstStamp) {
  const auto records = parseTumTextList(
      "\xEF\xBB\xBF"
      "1.5 rgb/1.png\n",
      "rgb.txt", kList);
  ASSERT_EQ(records.size(), 1u);
  EXPECT_DOUBLE_EQ(records[0].stamp, 1.5);
}

TEST(TumTextList, ALastLineCutOffIsLeftOutOnlyWhenAskedAndOnlyAtTheEnd) {
  const std::string cut_text = "1.0 rgb/1.png\n2.0 rgb/2.png\n3.0 rgb/";
  EXPECT_THROW(parseTumTextList("1.0 rgb/1.png\n3.0", "rgb.txt", kList), TumTextError);  // not asked
  std::string cut;
  auto records = parseTumTextList("1.0 rgb/1.png\n3.0", "rgb.txt", kList, &cut);
  ASSERT_EQ(records.size(), 1u);
  EXPECT_EQ(cut.rfind("rgb.txt:2: the last line, '3.0', has no end of line", 0), 0u) << cut;
  // A whole last line without an end of line is a record like any other.
  records = parseTumTextList(cut_text, "rgb.txt", kList, &cut);
  EXPECT_EQ(records.size(), 3u);
  EXPECT_EQ(cut, "");
  // A malformed last line that does end with a newline was written whole: still an error.
  EXPECT_THROW(parseTumTextList("1.0 rgb/1.png\n3.0\n", "rgb.txt", kList, &cut), TumTextError);
}

TEST(TumTextList, ReadsFilesAndNamesAnUnreadableOne) {
  const auto dir = test::scratchDir("tum_text_list");
  std::ofstream(dir / "depth.txt") << "# depth maps\n1.0 depth/1.png\n2.0 depth/2.png\n";
  EXPECT_EQ(readTumTextList((dir / "depth.txt").string(), kList).size(), 2u);
  try {
    readTumTextList("/nonexistent/depth.txt", kList);
    FAIL();
  } catch (const TumTextError& e) {
    EXPECT_STREQ(e.what(), "/nonexistent/depth.txt: cannot open list file");
  }
}

}  // namespace
}  // namespace bmp

#include <gtest/gtest.h>

#include "bmp/common/arg_parser.hpp"
#include "bmp/common/arg_range.hpp"

#include <limits>

namespace bmp {
namespace {

ArgParser makeParser() {
  ArgParser p("prog", "does things");
  p.addOption("speed", "X", "speed factor", "1.0");
  p.addOption("name", "S", "a name");
  p.addFlag("fast", "go fast");
  return p;
}

TEST(ArgParser, ParsesBothValueFormsAndFlags) {
  ArgParser p = makeParser();
  const char* argv[] = {"prog", "--speed", "2.5", "--name=x", "--fast"};
  ASSERT_TRUE(p.parse(5, argv));
  EXPECT_DOUBLE_EQ(p.number("speed"), 2.5);
  EXPECT_EQ(p.value("name"), "x");
  EXPECT_TRUE(p.flag("fast"));
}

// A value left out before another option: the option is not taken as the value (`--name --fast` named the
// run "--fast" and lost the flag). A value that starts with "--" but names no option, or given with '=',
// is a value.
TEST(ArgParser, AnOptionWhereAValueShouldBeIsAMissingValue) {
  {
    ArgParser p = makeParser();
    const char* argv[] = {"prog", "--name", "--fast"};
    try {
      p.parse(3, argv);
      FAIL() << "parsed";
    } catch (const ArgError& e) {
      EXPECT_EQ(std::string(e.what()), "prog: option '--name' needs a value S before '--fast'");
    }
  }
  {
    ArgParser p = makeParser();
    const char* argv[] = {"prog", "--name", "--speed=2"};
    EXPECT_THROW(p.parse(3, argv), ArgError);
  }
  {
    ArgParser p = makeParser();
    const char* argv[] = {"prog", "--name", "--not-an-option", "--speed", "-2", "--fast"};
    ASSERT_TRUE(p.parse(6, argv));
    EXPECT_EQ(p.value("name"), "--not-an-option");
    EXPECT_DOUBLE_EQ(p.number("speed"), -2.0);
  }
  {
    ArgParser p = makeParser();
    const char* argv[] = {"prog", "--name=--fast"};
    ASSERT_TRUE(p.parse(2, argv));
    EXPECT_EQ(p.value("name"), "--fast");
    EXPECT_FALSE(p.flag("fast"));
  }
}

TEST(ArgParser, DefaultsAndHelp) {
  ArgParser p = makeParser();
  const char* argv[] = {"prog", "--help"};
  EXPECT_FALSE(p.parse(2, argv));
  EXPECT_EQ(p.value("speed"), "1.0");
  const std::string help = p.help();
  EXPECT_NE(help.find("--speed X"), std::string::npos);
  EXPECT_NE(help.find("(default: 1.0)"), std::string::npos);
}

TEST(ArgParser, ErrorsNameTheOption) {
  {
    ArgParser p = makeParser();
    const char* argv[] = {"prog", "--sped", "2"};
    EXPECT_THROW(p.parse(3, argv), ArgError);
  }
  {
    ArgParser p = makeParser();
    const char* argv[] = {"prog", "--speed"};
    EXPECT_THROW(p.parse(2, argv), ArgError);
  }
  {
    ArgParser p = makeParser();
    const char* argv[] = {"prog", "--speed", "fast"};
    ASSERT_TRUE(p.parse(3, argv));
    try {
      p.number("speed");
      FAIL();
    } catch (const ArgError& e) {
      EXPECT_NE(std::string(e.what()).find("--speed"), std::string::npos);
    }
  }
}

TEST(ArgParser, ListSplitsAtCommasAndDropsEmptyItems) {
  ArgParser p("prog", "summary");
  p.addOption("names", "LIST", "comma-separated");
  p.addOption("none", "LIST", "comma-separated");
  const char* argv[] = {"prog", "--names", "a,b,,c,"};
  ASSERT_TRUE(p.parse(3, argv));
  EXPECT_EQ(p.list("names"), (std::vector<std::string>{"a", "b", "c"}));
  EXPECT_TRUE(p.list("none").empty());
}

// Ranged values: out of range (NaN and infinity included) is an ArgError naming option, range and value.
TEST(ArgRange, RefusesValuesOutsideTheRangeNamingOptionRangeAndValue) {
  ArgParser p("prog", "summary");
  p.addOption("conf", "X", "a probability");
  p.addOption("n", "N", "a count");
  const auto parse = [&p](const char* conf, const char* n) {
    const char* argv[] = {"prog", "--conf", conf, "--n", n};
    ASSERT_TRUE(p.parse(5, argv));
  };
  parse("0.5", "3");
  EXPECT_DOUBLE_EQ(numberIn(p, "conf", 0, 1), 0.5);
  EXPECT_DOUBLE_EQ(positiveNumber(p, "conf"), 0.5);
  EXPECT_EQ(integerIn(p, "n", 0, std::numeric_limits<long long>::max()), 3);
  for (const char* bad : {"5", "-1", "nan", "inf"}) {
    parse(bad, "-3");
    try {
      numberIn(p, "conf", 0, 1);
      ADD_FAILURE() << bad << " accepted";
    } catch (const ArgError& e) {
      EXPECT_EQ(std::string(e.what()),
                std::string("prog: --conf must be a number from 0 to 1, got '") + bad + "'");
    }
    if (std::string(bad) != "5") {
      EXPECT_THROW(positiveNumber(p, "conf"), ArgError) << bad;
    }
    if (std::string(bad) == "nan" || std::string(bad) == "inf") {  // no option takes them, ranged or not
      EXPECT_THROW(p.number("conf"), ArgError) << bad;
    }
  }
  try {
    integerIn(p, "n", 0, std::numeric_limits<long long>::max());
    ADD_FAILURE() << "-3 accepted";
  } catch (const ArgError& e) {
    EXPECT_EQ(std::string(e.what()), "prog: --n must be an integer of at least 0, got '-3'");
  }
  parse("0", "0");
  EXPECT_THROW(positiveNumber(p, "conf"), ArgError);
}

}  // namespace
}  // namespace bmp

#include <gtest/gtest.h>

#include "bmp/common/json_text.hpp"

namespace bmp {
namespace {

TEST(JsonText, QuotesAndEscapes) {
  EXPECT_EQ(jsonString("person"), "\"person\"");
  EXPECT_EQ(jsonString("a\"b\\c"), "\"a\\\"b\\\\c\"");
  EXPECT_EQ(jsonString("line\nnext\ttab"), "\"line\\nnext\\ttab\"");
  EXPECT_EQ(jsonString(std::string("\x01", 1)), "\"\\u0001\"");
  EXPECT_EQ(jsonString("Stuhl \xc3\xbc"), "\"Stuhl \xc3\xbc\"");  // UTF-8 passes through
}

}  // namespace
}  // namespace bmp

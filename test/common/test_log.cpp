// Log lines carry other programs' text (labels, reasons, source names off LCM): none of it may rewrite the
// terminal or pass for a line of our own.
#include <gtest/gtest.h>

#include <string>

#include "bmp/common/log.hpp"

namespace bmp {
namespace {

TEST(Log, ControlCharactersAreShownAndALineBreakIsIndented) {
  EXPECT_EQ(log::printable("box 0 (person)\tscore 0.9"), "box 0 (person)\tscore 0.9");
  EXPECT_EQ(log::printable("red \x1b[31mtext\x1b[0m\r\x7f"), "red ?[31mtext?[0m??");
  EXPECT_EQ(log::printable("label\n[12:00:00.000] [E] bmp-tracker: forged"),
            "label\n    [12:00:00.000] [E] bmp-tracker: forged");
  EXPECT_EQ(log::printable("caf\xc3\xa9"), "caf\xc3\xa9");  // UTF-8 passes as it is
  testing::internal::CaptureStderr();
  log::warn("answer for frame 4: box 0 (", std::string("a\nb\x1b"), ")");
  const std::string line = testing::internal::GetCapturedStderr();
  EXPECT_NE(line.find("] [W] answer for frame 4: box 0 (a\n    b?)\n"), std::string::npos) << line;
}

}  // namespace
}  // namespace bmp

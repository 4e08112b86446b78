// Text from files and callers: the UTF-8 check every stored string passes, and the printable form
// the CLI and error messages show.
#include <gtest/gtest.h>

#include <string>

#include "base/text.h"

using namespace mcon;
using namespace std::string_literals;

TEST(Text, WellFormedUtf8IsAccepted) {
  for (const std::string& s : {""s, "nose_07"s, "Gesicht \xc3\xbc"s, "\xe2\x82\xac 12"s, "\xf0\x9f\x91\x83"s,
                               "\xed\x9f\xbf"s /* U+D7FF */, "\xee\x80\x80"s /* U+E000 */,
                               "\xf4\x8f\xbf\xbf"s /* U+10FFFF */, "tab\there"s})
    EXPECT_EQ(invalid_utf8_offset(s), std::string::npos) << s;
}

TEST(Text, MalformedUtf8IsFoundAtItsFirstBadByte) {
  EXPECT_EQ(invalid_utf8_offset("ab\xff"), 2u);
  EXPECT_EQ(invalid_utf8_offset("\x80"), 0u);               // a lone continuation byte
  EXPECT_EQ(invalid_utf8_offset("x\xc3"), 1u);              // truncated sequence
  EXPECT_EQ(invalid_utf8_offset("\xc0\xaf"), 0u);           // overlong '/'
  EXPECT_EQ(invalid_utf8_offset("\xe0\x9f\xbf"), 0u);       // overlong 3-byte form
  EXPECT_EQ(invalid_utf8_offset("\xf0\x8f\xbf\xbf"), 0u);   // overlong 4-byte form
  EXPECT_EQ(invalid_utf8_offset("ok\xed\xa0\x80"), 2u);     // surrogate U+D800
  EXPECT_EQ(invalid_utf8_offset("\xf4\x90\x80\x80"), 0u);   // above U+10FFFF
  EXPECT_EQ(invalid_utf8_offset("\xf5\x80\x80\x80"), 0u);
  EXPECT_EQ(invalid_utf8_offset("\xc3\xbc\xe2\x82"), 2u);   // good, then truncated
}

TEST(Text, ProblemsNameTheOffset) {
  EXPECT_EQ(text_problem("nose"), "");
  EXPECT_EQ(text_problem("a\0b"s), "contains a NUL byte at offset 1");
  EXPECT_EQ(text_problem("abc\xff"), "is not valid UTF-8 (byte 0xff at offset 3)");
}

TEST(Text, PrintableEscapesControlsAndBadBytesOnly) {
  EXPECT_EQ(printable_text("nose_07"), "nose_07");
  EXPECT_EQ(printable_text("Gesicht \xc3\xbc \xe2\x82\xac"), "Gesicht \xc3\xbc \xe2\x82\xac");
  EXPECT_EQ(printable_text("a\x1b[2Jb"), "a\\x1b[2Jb");  // a terminal escape sequence
  EXPECT_EQ(printable_text("line\nnext\r\t"), "line\\nnext\\r\\t");
  EXPECT_EQ(printable_text("nul\0del\x7f"s), "nul\\x00del\\x7f");
  EXPECT_EQ(printable_text("c1 \xc2\x9b" "31m"), "c1 \\u009b31m");  // C1 CSI
  EXPECT_EQ(printable_text("\xc2\xa0"), "\xc2\xa0");                 // U+00A0 is printable
  EXPECT_EQ(printable_text("bad \xff\xc3"), "bad \\xff\\xc3");
  EXPECT_EQ(printable_text("back\\slash"), "back\\\\slash");  // unambiguous: "\x1b" typed out stays distinct
  EXPECT_EQ(invalid_utf8_offset(printable_text("\xff\x80\xed\xa0\x80")), std::string::npos);
}

TEST(Text, NumbersAreShownInFullPrecision) {
  EXPECT_EQ(number_text(1e-12), "1e-12");
  EXPECT_EQ(number_text(0.3), "0.3");
  EXPECT_EQ(number_text(2.0), "2");
  EXPECT_EQ(number_text(1.0 / 3.0), "0.3333333333333333");
}

// What the reader's messages say about odd input: line ends of old Macs,
// warnings that print as warnings, control bytes never echoed raw, malformed
// numbers and stray letters named for what they are.
#include <gtest/gtest.h>

#include <string>

#include "core/gcode/gcode_test_util.h"

namespace lcnc {
namespace {

using test::expect_error;
using test::run;
using test::segments;
using test::start_at;

// No byte below 0x20 (or DEL) in a message or its printed form.
void expect_printable(const Diagnostic& d) {
  const std::string s = d.to_string();
  for (const char ch : s) {
    const auto c = static_cast<unsigned char>(ch);
    EXPECT_TRUE(c >= 0x20 && c != 0x7F) << "raw byte 0x" << std::hex << unsigned{c} << " in: " << s;
  }
}

// --- line ends --------------------------------------------------------------

TEST(ProgramReaderMessages, LoneCarriageReturnEndsALine) {
  // old Mac files: "G1 X1\rG1 X2\r" are two blocks, not G1 and G1 in one
  const auto segs = segments("G1 X20 F600\rG1 X30\r");
  ASSERT_EQ(segs.size(), 2u);
  EXPECT_EQ(segs[1].line, 2u);
  // line numbers stay right: CRLF is one line end, a lone CR one more
  const Diagnostic d =
      expect_error("G1 X20 F600\r\nG1 X30\rG1 X40\r\n\rG1 X2000\r", ErrorCode::GcodeBeyondTravel, 5, 4);
  EXPECT_MENTIONS(d, "'G1 X2000'");
}

// --- warnings ---------------------------------------------------------------

TEST(ProgramReaderMessages, LinesAfterTheEndPrintAsAWarning) {
  const auto r = run("G1 X20 F600\nM30\nG1 X30\n");
  EXPECT_EQ(r.last, ProgramReader::Next::End);
  ASSERT_EQ(r.warnings.size(), 1u);
  const std::string s = r.warnings[0].to_string();
  EXPECT_EQ(s.rfind("test.ngc:3:1: warning E309 (GcodeLinesAfterEnd): ", 0), 0u) << s;
  // errors still print as errors
  const Diagnostic e = expect_error("G1 X10\n", ErrorCode::GcodeNoFeed, 1, 1);
  EXPECT_EQ(e.to_string().rfind("test.ngc:1:1: error E301", 0), 0u) << e.to_string();
}

TEST(ProgramReaderMessages, TextWithoutLineEndsAfterTheEndIsOnlyWarnedAbout) {
  const auto r = run("G1 X20 F600\nM30\n" + std::string(70000, '\0'));
  EXPECT_EQ(r.last, ProgramReader::Next::End);
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_MENTIONS(r.warnings[0], "the first longer than 65536 bytes");
  EXPECT_EQ(r.warnings[0].line, 3u);
}

// --- control bytes ----------------------------------------------------------

TEST(ProgramReaderMessages, ControlBytesAreEscapedInEveryExcerpt) {
  using namespace std::string_literals;
  // a NUL where a word should be (block parser)
  Diagnostic d = expect_error("G1 X10\0 F600\n"s, ErrorCode::GcodeSyntax, 1, 7);
  EXPECT_MENTIONS(d, "found '\\x00'");
  expect_printable(d);
  // an escape sequence in a comment, quoted with its block (interpreter)
  d = expect_error("G1 X20 (\x1b[2J\x1b[31m)\n", ErrorCode::GcodeNoFeed, 1, 1);
  EXPECT_MENTIONS(d, "'G1 X20 (\\x1B[2J\\x1B[31m)'");
  expect_printable(d);
  // after a letter with no number, and after '%'
  d = expect_error("G1 X\x07\n", ErrorCode::GcodeBadNumber, 1, 4);
  EXPECT_MENTIONS(d, "'X\\x07'");
  expect_printable(d);
  d = expect_error("%\x7f\n", ErrorCode::GcodeSyntax, 1, 2);
  EXPECT_MENTIONS(d, "'\\x7F'");
  expect_printable(d);
  // in the first line after the end (warning)
  const auto r = run("M30\nG0 X1\x1b]0;pwned\x07\n");
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_MENTIONS(r.warnings[0], "'G0 X1\\x1B]0;pwned\\x07'");
  expect_printable(r.warnings[0]);
}

// --- numbers and letters ----------------------------------------------------

TEST(ProgramReaderMessages, TwoDecimalPointsAreAMalformedNumber) {
  Diagnostic d = expect_error("G1 X1.2.3 F600\n", ErrorCode::GcodeBadNumber, 1, 4);
  EXPECT_MENTIONS(d, "found 'X1.2.3': malformed number '1.2.3' (more than one decimal point)");
  d = expect_error("G1 X-1.5-2 F600\n", ErrorCode::GcodeBadNumber, 1, 4);
  EXPECT_MENTIONS(d, "malformed number '-1.5-2' (a sign inside the number)");
  d = expect_error("G1 X.5. F600\n", ErrorCode::GcodeBadNumber, 1, 4);
  EXPECT_MENTIONS(d, "malformed number '.5.'");
  // the next word's sign is not part of the number
  segments("G1 X20 F600\nG1 X30Y+1\n");
}

TEST(ProgramReaderMessages, LetterOAfterANumberIsAStrayLetterNotAnOWord) {
  Diagnostic d = expect_error("G1 X1O F600\n", ErrorCode::GcodeSyntax, 1, 6);
  EXPECT_MENTIONS(d, "found a letter 'O' after 'X1'");
  EXPECT_MENTIONS(d, "unexpected 'O'");
  EXPECT_EQ(d.message.find("O-word subroutines"), std::string::npos) << d.message;
  // an O-word opening a block is read as one
  d = expect_error("O100 sub\n", ErrorCode::GcodeFlow, 1, 1);
  EXPECT_MENTIONS(d, "inside the definition of O100");
  d = expect_error("N10 O100 sub\n", ErrorCode::GcodeFlow, 1, 5);
  EXPECT_MENTIONS(d, "expected O100 endsub");
}

}  // namespace
}  // namespace lcnc

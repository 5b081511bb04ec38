// Every error of the reader: its code, line and column (1-based, in the line
// as written) and a message naming what was found and what was expected.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "core/gcode/gcode_test_util.h"

namespace lcnc {
namespace {

using test::expect_error;
using test::run;
using test::start_at;

// --- feed -----------------------------------------------------------------

TEST(ProgramReader, FeedMoveWithoutFIsError) {
  const Diagnostic d = expect_error("G1 X10\n", ErrorCode::GcodeNoFeed, 1, 1);
  EXPECT_MENTIONS(d, "found 'G1 X10' with no feed rate in effect");
  EXPECT_MENTIONS(d, "expected an F word (feed in mm/min) before or on this line");
  EXPECT_EQ(d.to_string().rfind("test.ngc:1:1: error E301 (GcodeNoFeed)", 0), 0u) << d.to_string();
}

TEST(ProgramReader, FeedMoveInInchesNamesInchesPerMinute) {
  const Diagnostic d = expect_error("G20\nG2 X1 Y1 R1\n", ErrorCode::GcodeNoFeed, 2, 1);
  EXPECT_MENTIONS(d, "in/min");
}

TEST(ProgramReader, ZeroFeedCountsAsNoFeed) {
  const Diagnostic d = expect_error("G0 X20\nF0\nG1 X30\n", ErrorCode::GcodeNoFeed, 3, 1);
  EXPECT_MENTIONS(d, "F0");
}

TEST(ProgramReader, NoFeedPointsAtTheFirstAxisWordWithModalMotion) {
  expect_error("G1\n  X20\n", ErrorCode::GcodeNoFeed, 2, 3);
}

TEST(ProgramReader, InverseTimeNeedsFOnEveryFeedMove) {
  Diagnostic d = expect_error("G93 G1 X20 F2\nX30\n", ErrorCode::GcodeNoFeed, 2, 1);
  EXPECT_MENTIONS(d, "G93");
  // F on a line without a feed move is not kept in G93.
  expect_error("G93 F2\nG1 X30\n", ErrorCode::GcodeNoFeed, 2, 1);
  d = expect_error("G93 G1 X20 F0\n", ErrorCode::GcodeNoFeed, 1, 5);
  EXPECT_MENTIONS(d, "F0");
}

TEST(ProgramReader, SwitchingFeedModeForgetsF) {
  expect_error("G1 X20 F600\nG93 G1 X30 F1\nG94 G1 X40\n", ErrorCode::GcodeNoFeed, 3, 5);
  expect_error("G1 X20 F600\nG93\nG1 X30\n", ErrorCode::GcodeNoFeed, 3, 1);
}

TEST(ProgramReader, NegativeFeedIsBadValue) {
  const Diagnostic d = expect_error("G1 X20 F-100\n", ErrorCode::GcodeBadValue, 1, 8);
  EXPECT_MENTIONS(d, "F-100");
}

// --- motion mode, axes, travel --------------------------------------------

TEST(ProgramReader, AxisWordsWithNoMotionModeIsError) {
  Diagnostic d = expect_error("X10\n", ErrorCode::GcodeNoMotionMode, 1, 1);
  EXPECT_MENTIONS(d, "'X10'");
  EXPECT_MENTIONS(d, "G0, G1, G2 or G3");
  expect_error("F100 Y10\n", ErrorCode::GcodeNoMotionMode, 1, 6);
}

TEST(ProgramReader, AxisTheMachineLacksIsError) {
  const Diagnostic d = expect_error("G0 X20 B10\n", ErrorCode::GcodeNoSuchAxis, 1, 8);
  EXPECT_MENTIONS(d, "no B axis");
  EXPECT_MENTIONS(d, "X Y Z A C");
}

TEST(ProgramReader, MoveBeyondTravelIsError) {
  Diagnostic d = expect_error("G0 X1200\n", ErrorCode::GcodeBeyondTravel, 1, 4);
  EXPECT_MENTIONS(d, "X to 1200 mm");
  EXPECT_MENTIONS(d, "[0, 1000]");
  d = expect_error("G91 G0 Y-20\n", ErrorCode::GcodeBeyondTravel, 1, 8);
  EXPECT_MENTIONS(d, "Y to -10 mm");
  d = expect_error("G0 A100\n", ErrorCode::GcodeBeyondTravel, 1, 4);
  EXPECT_MENTIONS(d, "A to 100 deg");
  EXPECT_MENTIONS(d, "[-95, 95]");
  expect_error("G0 X1000.000001\n", ErrorCode::GcodeBeyondTravel, 1, 4);
}

TEST(ProgramReader, WorkOffsetCanPushAMoveBeyondTravel) {
  const Diagnostic d = expect_error("G55 G0 X600\n", ErrorCode::GcodeBeyondTravel, 1, 8);
  EXPECT_MENTIONS(d, "X to 1100 mm");
}

TEST(ProgramReader, InchMoveBeyondTravelIsError) {
  expect_error("G20 G0 Y20\n", ErrorCode::GcodeBeyondTravel, 1, 8);  // 508 mm > 450
}

TEST(ProgramReader, ArcPassingBeyondTravelIsErrorEvenWithEndsInside) {
  // Centre (10, 80), radius 20: G3 from the top passes X = -10.
  const Diagnostic d =
      expect_error("G3 X10 Y60 J-20 F600\n", ErrorCode::GcodeBeyondTravel, 1, 1, start_at(10, 100, 10));
  EXPECT_MENTIONS(d, "X to -10 mm (arc extreme)");
  // G2 between the same points passes X = 30 instead: fine.
  EXPECT_EQ(test::segments("G2 X10 Y60 J-20 F600\n", start_at(10, 100, 10)).size(), 1u);
}

TEST(ProgramReader, HelixNormalAxisBeyondTravelIsError) {
  const Diagnostic d = expect_error("G2 X100 Y100 Z600 I10 F600\n", ErrorCode::GcodeBeyondTravel, 1, 14,
                                    start_at(100, 100, 10));
  EXPECT_MENTIONS(d, "Z to 600 mm");
}

// --- arcs -----------------------------------------------------------------

TEST(ProgramReader, ArcRadiusTooSmallIsError) {
  const Diagnostic d =
      expect_error("G2 X120 Y100 R5 F600\n", ErrorCode::GcodeArcRadius, 1, 14, start_at(100, 100, 10));
  EXPECT_MENTIONS(d, "'R5'");
  EXPECT_MENTIONS(d, "20 mm from the start");
  EXPECT_MENTIONS(d, "expected |R| >= 10 mm");
  expect_error("G2 X120 Y100 R9.99 F600\n", ErrorCode::GcodeArcRadius, 1, 14, start_at(100, 100, 10));
}

TEST(ProgramReader, RadiusFormFullCircleIsError) {
  const Diagnostic d =
      expect_error("G2 X100 Y100 R10 F600\n", ErrorCode::GcodeArcRadius, 1, 14, start_at(100, 100, 10));
  EXPECT_MENTIONS(d, "full circle");
}

TEST(ProgramReader, ArcRadiiToStartAndEndMustAgree) {
  const Diagnostic d =
      expect_error("G2 X110 Y90 I0 J-10.1 F600\n", ErrorCode::GcodeArcRadius, 1, 13, start_at(100, 100, 10));
  EXPECT_MENTIONS(d, "radius 10.1 mm to the start");
  EXPECT_MENTIONS(d, "10.0005 mm to the end");
}

TEST(ProgramReader, ArcRadiusDifferenceAboveHardLimitIsError) {
  // Radius 4000 and 4003.9: 0.097 % is within the relative tolerance but
  // 3.9 mm exceeds 100 × 0.0283 mm (LinuxCNC refuses it; 4002.8 it accepts).
  MachineConfig wide = test::test_machine();
  wide.axis(Axis::X).min = -1.0;  // the spiral's radius grows at once: it starts at X −0.0001
  wide.axis(Axis::X).max = 9000.0;
  wide.axis(Axis::Y).min = -4100.0;
  wide.axis(Axis::Y).max = 4100.0;
  const std::string refused = "G3 X8003.9 Y0 I4000 J0 F600\n";
  const auto col = static_cast<std::uint32_t>(refused.find('I') + 1);
  const Diagnostic d = expect_error(refused, ErrorCode::GcodeArcRadius, 1, col, start_at(0, 0, 10), wide);
  EXPECT_MENTIONS(d, "up to 2.82843 mm");
  EXPECT_EQ(test::segments("G3 X8002.8 Y0 I4000 J0 F600\n", start_at(0, 0, 10), wide).size(), 1u);
}

TEST(ProgramReader, ArcCentreOnItsStartIsError) {
  const Diagnostic d =
      expect_error("G2 X110 Y100 I0 J0 F600\n", ErrorCode::GcodeArcRadius, 1, 14, start_at(100, 100, 10));
  EXPECT_MENTIONS(d, "radius 0");
}

TEST(ProgramReader, ArcWithoutCentreOrRadiusIsError) {
  Diagnostic d =
      expect_error("G2 X110 Y90 F600\n", ErrorCode::GcodeArcMissingCenter, 1, 1, start_at(100, 100, 10));
  EXPECT_MENTIONS(d, "expected I J");
  EXPECT_MENTIONS(d, "or R");
  d = expect_error("G18 G3 X20 Z20 F600\n", ErrorCode::GcodeArcMissingCenter, 1, 5);
  EXPECT_MENTIONS(d, "expected K I");
}

// LinuxCNC 2.9: G2/G3 with a centre and no axis words is a full circle at
// the current point; with neither, or with R alone, an error.
TEST(ProgramReader, ArcWithoutAxisWordsIsAFullCircleAtTheCurrentPoint) {
  const auto segs = test::segments("G2 I10 F600\nG18 G3 K-5\n");
  ASSERT_EQ(segs.size(), 2u);
  EXPECT_EQ(segs[0].kind, MotionKind::Arc);
  EXPECT_EQ(segs[0].end, segs[0].start);
  EXPECT_DOUBLE_EQ(segs[0].center[0], 20.0);  // from X10 Y10
  EXPECT_DOUBLE_EQ(segs[0].center[1], 10.0);
  EXPECT_TRUE(segs[0].clockwise);
  EXPECT_DOUBLE_EQ(segs[1].center[2], 5.0);
  EXPECT_FALSE(segs[1].clockwise);
  Diagnostic d = expect_error("G2 F600\n", ErrorCode::GcodeArcMissingCenter, 1, 1);
  EXPECT_MENTIONS(d, "or R");
  d = expect_error("G2 R5 F600\n", ErrorCode::GcodeArcRadius, 1, 4);
  EXPECT_MENTIONS(d, "full circle");
}

TEST(ProgramReader, CentreWordOfTheNormalAxisIsError) {
  const Diagnostic d =
      expect_error("G2 X110 Y90 J-10 K1 F600\n", ErrorCode::GcodeSyntax, 1, 18, start_at(100, 100, 10));
  EXPECT_MENTIONS(d, "XY plane (G17)");
  expect_error("G19 G2 Y20 Z20 I5 F600\n", ErrorCode::GcodeSyntax, 1, 16);
}

TEST(ProgramReader, RadiusAndCentreTogetherIsError) {
  const Diagnostic d =
      expect_error("G2 X110 Y90 I0 R10 F600\n", ErrorCode::GcodeSyntax, 1, 16, start_at(100, 100, 10));
  EXPECT_MENTIONS(d, "either R or I J");
}

TEST(ProgramReader, ArcTurnsMustBeAPositiveWholeNumber) {
  Diagnostic d =
      expect_error("G2 X100 Y100 I10 P0 F600\n", ErrorCode::GcodeBadValue, 1, 18, start_at(100, 100, 10));
  EXPECT_MENTIONS(d, "whole number of turns");
  expect_error("G2 X100 Y100 I10 P1.5 F600\n", ErrorCode::GcodeBadValue, 1, 18, start_at(100, 100, 10));
  // found by libFuzzer (UBSan): a P too large for any count of turns was
  // converted to an integer before it was checked
  d = expect_error("G2 X100 Y100 I10 P3482879571417046128 F600\n", ErrorCode::GcodeBadValue, 1, 18,
                   start_at(100, 100, 10));
  EXPECT_MENTIONS(d, "turns from 1 to 10000");
}

TEST(ProgramReader, CentreWordsWithoutAnArcAreError) {
  Diagnostic d = expect_error("G1 X20 I5 F600\n", ErrorCode::GcodeUnsupported, 1, 8);
  EXPECT_MENTIONS(d, "'I5' with no G2 or G3");
  expect_error("G0 X20 R5\n", ErrorCode::GcodeUnsupported, 1, 8);
  expect_error("G2 X20 Y10 I5 F600\nI5\n", ErrorCode::GcodeUnsupported, 2, 1, start_at(10, 10, 10));
}

// --- dwell, P, Q, S -------------------------------------------------------

TEST(ProgramReader, DwellWithoutPIsMissingWord) {
  Diagnostic d = expect_error("G4\n", ErrorCode::GcodeMissingWord, 1, 1);
  EXPECT_MENTIONS(d, "G4 P<seconds>");
  expect_error("G0 X20\nG1 F600 G4\n", ErrorCode::GcodeMissingWord, 2, 9);
}

TEST(ProgramReader, NegativeDwellIsBadValue) {
  const Diagnostic d = expect_error("G4 P-1\n", ErrorCode::GcodeBadValue, 1, 4);
  EXPECT_MENTIONS(d, "P >= 0 seconds");
}

TEST(ProgramReader, PWithNothingToUseItIsError) {
  const Diagnostic d = expect_error("G1 X20 P5 F600\n", ErrorCode::GcodeUnsupported, 1, 8);
  EXPECT_MENTIONS(d, "G4");
  EXPECT_MENTIONS(d, "G64");
}

TEST(ProgramReader, QOutsideG64IsError) {
  const Diagnostic d = expect_error("G1 X20 Q1 F600\n", ErrorCode::GcodeUnsupported, 1, 8);
  EXPECT_MENTIONS(d, "G64");
}

TEST(ProgramReader, NegativeBlendToleranceIsBadValue) {
  expect_error("G64 P-1\n", ErrorCode::GcodeBadValue, 1, 5);
  expect_error("G64 P1 Q-1\n", ErrorCode::GcodeBadValue, 1, 8);
}

TEST(ProgramReader, PowerAboveSMaxOrNegativeIsBadValue) {
  Diagnostic d = expect_error("S120\n", ErrorCode::GcodeBadValue, 1, 1);
  EXPECT_MENTIONS(d, "'S120'");
  EXPECT_MENTIONS(d, "expected S from 0 to 100");
  expect_error("M3 S-5\n", ErrorCode::GcodeBadValue, 1, 4);
}

// --- codes and words outside the subset -----------------------------------

TEST(ProgramReader, UnknownGCodeIsNamed) {
  Diagnostic d = expect_error("G38.2 X10\n", ErrorCode::GcodeUnknownCode, 1, 1);
  EXPECT_EQ(d.message.rfind("G38.2 is not supported", 0), 0u) << d.message;
  EXPECT_MENTIONS(d, "G61.1");  // lists what is supported
  d = expect_error("G1 G84 X1 Y1 Z-1 R1\n", ErrorCode::GcodeUnknownCode, 1, 4);
  EXPECT_MENTIONS(d, "G84 is not supported (tapping reverses a spindle; a laser has none)");
  d = expect_error("G88 X1 Y1 Z-1 R1\n", ErrorCode::GcodeUnknownCode, 1, 1);
  EXPECT_MENTIONS(d, "manual retract");
  d = expect_error("G59.4\n", ErrorCode::GcodeUnknownCode, 1, 1);
  EXPECT_MENTIONS(d, "G59.4 is not supported");
  d = expect_error("G1.25\n", ErrorCode::GcodeUnknownCode, 1, 1);
  EXPECT_MENTIONS(d, "G1.25 is not supported");
}

TEST(ProgramReader, UnknownMCodeIsNamed) {
  Diagnostic d = expect_error("G0 X20\nM19\n", ErrorCode::GcodeUnknownCode, 2, 1);
  EXPECT_EQ(d.message.rfind("M19 is not supported", 0), 0u) << d.message;
  EXPECT_MENTIONS(d, "M30");
  d = expect_error("M3.5\n", ErrorCode::GcodeBadNumber, 1, 1);
  EXPECT_MENTIONS(d, "'M3.5'");
}

TEST(ProgramReader, ACallOfASubroutineNeverDefinedIsAnErrorAtTheCall) {
  Diagnostic d = expect_error("G1 X20 F600\nN10 o100 call\n", ErrorCode::GcodeFlow, 2, 5);
  EXPECT_MENTIONS(d, "subroutine O100 not found");
}

TEST(ProgramReader, OtherLettersAreUnsupportedAndSaySo) {
  Diagnostic d = expect_error("G1 U10\n", ErrorCode::GcodeUnsupported, 1, 4);
  EXPECT_MENTIONS(d, "U V W axes are not supported");
  // H and L belong to codes: alone they are named with what would use them
  d = expect_error("D1\n", ErrorCode::GcodeUnsupported, 1, 1);
  EXPECT_MENTIONS(d, "'D1' with no G41, G42, G41.1 or G42.1 to use it");
  d = expect_error("H1\n", ErrorCode::GcodeUnsupported, 1, 1);
  EXPECT_MENTIONS(d, "with no G43 or G43.2");
  d = expect_error("G1 X2 F100 L2\n", ErrorCode::GcodeUnsupported, 1, 12);
  EXPECT_MENTIONS(d, "with no G10");
  expect_error("E5\n", ErrorCode::GcodeUnsupported, 1, 1);
}

TEST(ProgramReader, RepeatedWordIsError) {
  Diagnostic d = expect_error("G1 X10 X20 F600\n", ErrorCode::GcodeRepeatedWord, 1, 8);
  EXPECT_MENTIONS(d, "second X word 'X20' (the first is 'X10')");
  expect_error("G1 X10 F600 F700\n", ErrorCode::GcodeRepeatedWord, 1, 13);
  expect_error("S1 S2\n", ErrorCode::GcodeRepeatedWord, 1, 4);
}

TEST(ProgramReader, TwoCodesOfOneModalGroupConflict) {
  Diagnostic d = expect_error("G0 G1 X10\n", ErrorCode::GcodeModalConflict, 1, 4);
  EXPECT_MENTIONS(d, "found G0 and G1 in one block, both of modal group 1 (motion)");
  expect_error("G1 G1 X10 F600\n", ErrorCode::GcodeModalConflict, 1, 4);
  expect_error("G90 G91\n", ErrorCode::GcodeModalConflict, 1, 5);
  expect_error("G90.1 G91.1\n", ErrorCode::GcodeModalConflict, 1, 7);
  expect_error("G17 G19\n", ErrorCode::GcodeModalConflict, 1, 5);
  expect_error("G20 G21\n", ErrorCode::GcodeModalConflict, 1, 5);
  expect_error("G93 G94\n", ErrorCode::GcodeModalConflict, 1, 5);
  expect_error("G54 G59\n", ErrorCode::GcodeModalConflict, 1, 5);
  d = expect_error("G61 G64\n", ErrorCode::GcodeModalConflict, 1, 5);
  EXPECT_MENTIONS(d, "group 13");
  d = expect_error("M3 M5\n", ErrorCode::GcodeModalConflict, 1, 4);
  EXPECT_MENTIONS(d, "found M3 and M5");
  expect_error("M8 M9\n", ErrorCode::GcodeModalConflict, 1, 4);
  expect_error("M9 M7\n", ErrorCode::GcodeModalConflict, 1, 4);
  expect_error("M7 M7\n", ErrorCode::GcodeModalConflict, 1, 4);
  expect_error("M2 M30\n", ErrorCode::GcodeModalConflict, 1, 4);
}

TEST(ProgramReader, CodesOfDifferentGroupsMayShareABlock) {
  const auto segs = test::segments("G90 G17 G21 G54 G64 G94 G91.1 G1 X20 F600 M3 M7 M8 S5\n");
  ASSERT_EQ(segs.size(), 1u);
}

// --- comments, numbers, syntax --------------------------------------------

TEST(ProgramReader, NestedCommentIsError) {
  const Diagnostic d = expect_error("G1 (a (b) c) X10\n", ErrorCode::GcodeComment, 1, 7);
  EXPECT_MENTIONS(d, "do not nest");
}

TEST(ProgramReader, UnclosedCommentIsError) {
  const Diagnostic d = expect_error("G0 X20\nG1 (a\n", ErrorCode::GcodeComment, 2, 4);
  EXPECT_MENTIONS(d, "not closed");
  expect_error("G1 X10)\n", ErrorCode::GcodeComment, 1, 7);
}

TEST(ProgramReader, MissingNumberIsBadNumber) {
  Diagnostic d = expect_error("G1 X F600\n", ErrorCode::GcodeBadNumber, 1, 4);
  EXPECT_MENTIONS(d, "no number after X");
  expect_error("G\n", ErrorCode::GcodeBadNumber, 1, 1);
  expect_error("G1 X-\n", ErrorCode::GcodeBadNumber, 1, 4);
  expect_error("G1 X.\n", ErrorCode::GcodeBadNumber, 1, 4);
}

TEST(ProgramReader, NumberTooLargeForADoubleIsBadNumber) {
  const Diagnostic d = expect_error("G1 X" + std::string(400, '9') + "\n", ErrorCode::GcodeBadNumber, 1, 4);
  EXPECT_MENTIONS(d, "out of range");
}

TEST(ProgramReader, StrayCharactersAreSyntaxErrors) {
  Diagnostic d = expect_error("G1 X10 * 2\n", ErrorCode::GcodeSyntax, 1, 8);
  EXPECT_MENTIONS(d, "found '*'");
  d = expect_error("G1 /X10\n", ErrorCode::GcodeSyntax, 1, 4);
  EXPECT_MENTIONS(d, "block delete");
  d = expect_error("% G1\n", ErrorCode::GcodeSyntax, 1, 3);
  EXPECT_MENTIONS(d, "'%'");
  d = expect_error("G1 N10 X20\n", ErrorCode::GcodeSyntax, 1, 4);
  EXPECT_MENTIONS(d, "line number N first");
  // a second decimal point is a malformed number, at its word
  // (program_reader_messages_test)
  expect_error("G1 X1.2.3\n", ErrorCode::GcodeBadNumber, 1, 4);
}

TEST(ProgramReader, ColumnCountsTheLineAsWritten) {
  // Blanks inside words and UTF-8 in comments: the column is in characters.
  expect_error("G 1  X 1 0 X5\n", ErrorCode::GcodeRepeatedWord, 1, 12);
  expect_error("(\xC3\xA9) D1\n", ErrorCode::GcodeUnsupported, 1, 5);
  expect_error("\tD1\n", ErrorCode::GcodeUnsupported, 1, 2);
}

TEST(ProgramReader, ErrorReportsItsOwnLine) {
  expect_error("G0 X20\n\n(c)\nG0 X2000\n", ErrorCode::GcodeBeyondTravel, 4, 4);
}

TEST(ProgramReader, LinesAfterTheEndAreNotChecked) {
  const auto r = run("M2\nT1\n");
  EXPECT_EQ(r.last, ProgramReader::Next::End);
  EXPECT_EQ(r.warnings.size(), 1u);
}

TEST(ProgramReader, BlockDeleteLinesAreStillParsed) {
  ReaderOptions on = start_at();
  on.block_delete = true;
  expect_error("/G1 X10 U1\n", ErrorCode::GcodeUnsupported, 1, 9, on);
}

TEST(ProgramReader, OpenMissingFileIsFileNotFound) {
  auto r = ProgramReader::open("/nonexistent/dir/part.ngc", test::test_machine());
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, ErrorCode::FileNotFound);
  EXPECT_EQ(r.error().file, "/nonexistent/dir/part.ngc");
  EXPECT_MENTIONS(r.error(), "part.ngc");
}

TEST(ProgramReader, ReadFailureIsAnErrorNotAnEarlyEnd) {
  // A directory opens but cannot be read: the program must not look empty.
  auto r = ProgramReader::open(::testing::TempDir(), test::test_machine());
  ASSERT_TRUE(r.ok()) << r.error().to_string();
  Segment s;
  EXPECT_EQ((*r)->next(s), ProgramReader::Next::Error);
  EXPECT_EQ((*r)->error().code, ErrorCode::FileNotFound);
  EXPECT_MENTIONS((*r)->error(), "reading stopped after line 0");
}

}  // namespace
}  // namespace lcnc

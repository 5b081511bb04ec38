// Values a machine could never finish or that are no numbers a program means:
// feeds, dwells, positions of axes no travel check covers, helix turns and
// lengths, path tolerances, line lengths. Each is refused with the bound it
// broke; values at the bound still run.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "core/gcode/gcode_test_util.h"
#include "gcode/gcode_tolerances.h"

namespace lcnc {
namespace {

using test::expect_error;
using test::run;
using test::segments;
using test::start_at;

// --- feed (G94) -------------------------------------------------------------

TEST(ProgramReaderBounds, FeedBelowOneMicronPerMinuteIsRefused) {
  // F0.000000001 would move X at the axis' full speed after the planner's
  // clamp, or not at all: neither is what the program says.
  const Diagnostic d =
      expect_error("G21 G90\nG1 X10 F0.000000001\nG1 X20 Y5 F600\nM30\n", ErrorCode::GcodeBadValue, 2, 8);
  EXPECT_MENTIONS(d, "'F0.000000001'");
  EXPECT_MENTIONS(d, "expected a feed rate F from 0.001 to 1e+07 mm/min");
  expect_error("G1 X10 Y10 F0.000000000000001\n", ErrorCode::GcodeBadValue, 1, 12);
  // at the bound it runs (1 µm at 1 µm/min: one minute)
  segments("G1 X10.001 F0.001\n");
}

TEST(ProgramReaderBounds, FeedBoundsInInchesAreSaidInInches) {
  const Diagnostic d = expect_error("G20 G1 X1 F0.00001\n", ErrorCode::GcodeBadValue, 1, 11);
  EXPECT_MENTIONS(d, "in/min");
  EXPECT_MENTIONS(d, "3.93701e-05");
}

TEST(ProgramReaderBounds, AbsurdlyLargeFeedIsRefused) {
  const std::string huge = "F1" + std::string(300, '0');  // 1e300
  Diagnostic d = expect_error("G1 X20 " + huge + "\n", ErrorCode::GcodeBadValue, 1, 8);
  EXPECT_MENTIONS(d, "to 1e+07 mm/min");
  expect_error("G1 X20 F10000001\n", ErrorCode::GcodeBadValue, 1, 8);
  segments("G1 X20 F10000000\n");
}

TEST(ProgramReaderBounds, AMoveLongerThanADayIsRefused) {
  // 990 mm at 0.5 mm/min: 1980 minutes
  Diagnostic d = expect_error("F0.5\nG1 X1000\n", ErrorCode::GcodeBadValue, 2, 1);
  EXPECT_MENTIONS(d, "a move of 990 mm at F0.5 takes 1980 minutes");
  EXPECT_MENTIONS(d, "at most 1440 minutes (one day)");
  // the same on the F word's line points at F
  expect_error("G1 X1000 F0.5\n", ErrorCode::GcodeBadValue, 1, 10);
  // a rotary-only move: deg at deg/min (A from 0 to 90 at 0.05 deg/min: 1800 min)
  expect_error("G1 A90 F0.05\n", ErrorCode::GcodeBadValue, 1, 8);
  // an arc: a half circle of radius 100 (314 mm) at 0.2 mm/min is 1571 minutes
  expect_error("G2 X210 Y10 I100 F0.2\n", ErrorCode::GcodeBadValue, 1, 18);
  segments("G1 X1000 F1\n");  // 990 minutes
}

// --- feed (G93) -------------------------------------------------------------

TEST(ProgramReaderBounds, InverseTimeFeedMustGiveAMoveOfAtMostADay) {
  // F = 1 / minutes: F0.000000001 is a move of 10^9 minutes
  Diagnostic d = expect_error("G93 G1 X10 F0.000000001\n", ErrorCode::GcodeBadValue, 1, 12);
  EXPECT_MENTIONS(d, "a move of 1e+09 minutes");
  EXPECT_MENTIONS(d, "expected F from 0.000694444 to 1e+07");
  expect_error("G93 G1 X20 F0.0006\n", ErrorCode::GcodeBadValue, 1, 12);  // 1667 minutes
  expect_error("G93 G1 X20 F10000001\n", ErrorCode::GcodeBadValue, 1, 12);
  segments("G93 G1 X20 F0.0007\n");  // 1429 minutes
}

// --- dwell ------------------------------------------------------------------

TEST(ProgramReaderBounds, DwellLongerThanADayIsRefused) {
  const Diagnostic d = expect_error("G4 P999999999999999\n", ErrorCode::GcodeBadValue, 1, 4);
  EXPECT_MENTIONS(d, "expected a dwell time P from 0 to 86400 seconds (one day)");
  expect_error("G4 P86400.001\n", ErrorCode::GcodeBadValue, 1, 4);
  const auto segs = segments("G4 P86400\n");
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_EQ(segs[0].dwell_s, 86400.0);
}

// --- positions --------------------------------------------------------------

TEST(ProgramReaderBounds, ContinuousRotaryPositionIsBounded) {
  // C is continuous on the test machine: no travel to check, yet 10^25
  // degrees is no position.
  const std::string c25 = "C1" + std::string(25, '0');
  Diagnostic d = expect_error("G0 " + c25 + "\n", ErrorCode::GcodeBadValue, 1, 4);
  EXPECT_MENTIONS(d, "moving C to 1e+25 deg");
  EXPECT_MENTIONS(d, "expected |C| <= 1e+07 deg");
  // incremental moves add up to the same bound
  expect_error("G91 G0 C9000000\nC9000000\n", ErrorCode::GcodeBadValue, 2, 1);
  segments("G0 C10000000\nG0 C-10000000\n");
}

TEST(ProgramReaderBounds, LinearPositionUnderToolCentrePointIsBounded) {
  // Under TCP the X Y Z travel is checked on the joints later; the words
  // still must be positions.
  MachineConfig m = test::test_machine();
  m.tcp.enabled = true;
  Diagnostic d = expect_error("G0 X2000000\n", ErrorCode::GcodeBadValue, 1, 4, start_at(), m);
  EXPECT_MENTIONS(d, "expected |X| <= 1e+06 mm");
  // without TCP the travel check says it, as before
  expect_error("G0 X2000000\n", ErrorCode::GcodeBeyondTravel, 1, 4);
}

// --- arcs -------------------------------------------------------------------

TEST(ProgramReaderBounds, HelixTurnsAreBounded) {
  Diagnostic d = expect_error("G2 X100 Y100 I10 P100000 F600\n", ErrorCode::GcodeBadValue, 1, 18,
                              start_at(100, 100, 10));
  EXPECT_MENTIONS(d, "turns from 1 to 10000");
  expect_error("G2 X100 Y100 I10 P10001 F600\n", ErrorCode::GcodeBadValue, 1, 18, start_at(100, 100, 10));
  const auto segs = segments("G2 X100 Y100 I1 P10000 F60000\n", start_at(100, 100, 10));
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_EQ(segs[0].extra_turns, 9999u);
}

TEST(ProgramReaderBounds, ArcLengthIsBounded) {
  // radius 200: 1257 mm a turn; 1000 turns are 1.26 km
  Diagnostic d = expect_error("G2 X300 Y225 I200 P1000 F100000\n", ErrorCode::GcodeBadValue, 1, 19,
                              start_at(300, 225, 10));
  EXPECT_MENTIONS(d, "an arc of 1.25664e+06 mm (radius 200 mm, 1000 turns)");
  EXPECT_MENTIONS(d, "expected an arc of at most 1e+06 mm");
  segments("G2 X300 Y225 I200 P700 F100000\n", start_at(300, 225, 10));
}

// --- path control -----------------------------------------------------------

TEST(ProgramReaderBounds, PathToleranceIsBounded) {
  Diagnostic d = expect_error("G64 P1000000000000000\n", ErrorCode::GcodeBadValue, 1, 5);
  EXPECT_MENTIONS(d, "expected a blend tolerance P from 0 to 10 mm");
  d = expect_error("G64 P0.1 Q11\n", ErrorCode::GcodeBadValue, 1, 10);
  EXPECT_MENTIONS(d, "naive-CAM tolerance Q from 0 to 10 mm");
  // inches: P0.5 in = 12.7 mm
  d = expect_error("G20 G64 P0.5\n", ErrorCode::GcodeBadValue, 1, 9);
  EXPECT_MENTIONS(d, "from 0 to 0.393701 in (10 mm)");
  const auto segs = segments("G64 P10 Q10\nG1 X20 F600\n");
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_EQ(segs[0].blend_tolerance_mm, 10.0);
}

// --- line length ------------------------------------------------------------

TEST(ProgramReaderBounds, OverlongLineIsAnErrorNamingTheLimit) {
  const std::string text = "G0 X20\nG0 X30\n" + std::string(gcode::kMaxLineBytes + 1, 'X') + "\nG0 X40\n";
  const auto r = run(text);
  EXPECT_EQ(r.last, ProgramReader::Next::Error);
  EXPECT_EQ(r.error.code, ErrorCode::GcodeSyntax);
  EXPECT_EQ(r.error.line, 3u);
  EXPECT_MENTIONS(r.error, "found a line longer than 65536 bytes");
  ASSERT_EQ(r.segments.size(), 2u);  // what came before was read
  // a line of exactly the bound is read (and parsed as usual)
  const std::string at_bound = "G0 X20 (" + std::string(gcode::kMaxLineBytes - 9, 'c') + ")\n";
  ASSERT_EQ(at_bound.size(), gcode::kMaxLineBytes + 1);
  EXPECT_EQ(segments(at_bound).size(), 1u);
}

}  // namespace
}  // namespace lcnc

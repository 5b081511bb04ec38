// Canned cycles as LinuxCNC runs them (tests/data/linuxcnc_compare/
// canned_cycles.ngc runs every case through LinuxCNC's own interpreter in
// the e2e comparison; these say what a laser user relies on, one by one).
#include <gtest/gtest.h>

#include "core/gcode/gcode_test_util.h"

namespace lcnc {
namespace {

using test::expect_error;
using test::pose;
using test::segments;
using test::start_at;

std::string kinds(const std::vector<Segment>& segs) {
  std::string k;
  for (const Segment& s : segs)
    k += s.kind == MotionKind::Rapid    ? 'r'
         : s.kind == MotionKind::Linear ? 'f'
         : s.kind == MotionKind::Dwell  ? 'd'
                                        : 'a';
  return k;
}

TEST(CannedCycles, G81DrillsEachHoleFromRAndReturnsToR) {
  // from (10, 10, 10): over the hole at Z10, down to R2, feed to Z-1, back to R2;
  // the next hole (X only) moves at R
  const auto segs = segments("G81 X20 Y30 Z1 R2 F300\nX40\n");
  EXPECT_EQ(kinds(segs), "rrfrrfr");
  EXPECT_POSE_NEAR(segs[0].end, pose(20, 30, 10), 1e-12);
  EXPECT_POSE_NEAR(segs[1].end, pose(20, 30, 2), 1e-12);
  EXPECT_POSE_NEAR(segs[2].end, pose(20, 30, 1), 1e-12);
  EXPECT_DOUBLE_EQ(segs[2].feed_mm_s, 5.0);
  EXPECT_POSE_NEAR(segs[3].end, pose(20, 30, 2), 1e-12);
  EXPECT_POSE_NEAR(segs[4].end, pose(40, 30, 2), 1e-12);
  EXPECT_POSE_NEAR(segs[6].end, pose(40, 30, 2), 1e-12);
}

TEST(CannedCycles, G82IsPercussionTheBeamOnThroughTheDwellAndOffOnTheRapids) {
  const auto segs = segments("M3 S80\nG98 G82 X20 Y30 Z1 R2 P0.4 F300\n");
  ASSERT_EQ(kinds(segs), "rrfdr");
  EXPECT_EQ(segs[2].laser, LaserMode::Constant);
  EXPECT_EQ(segs[3].laser, LaserMode::Constant);
  EXPECT_DOUBLE_EQ(segs[3].dwell_s, 0.4);
  EXPECT_DOUBLE_EQ(segs[3].power_pct, 80.0);
  EXPECT_EQ(segs[4].laser, LaserMode::Off);
  EXPECT_DOUBLE_EQ(segs[4].end[2], 10.0);  // G98: back to where Z stood
}

// G86 (boring: spindle stop at the bottom, rapid out) on a laser: G82's
// moves — the beam on down and through the dwell, off on the rapid out —
// and, as LinuxCNC with the spindle off, refused with the beam off.
TEST(CannedCycles, G86BoresWithTheBeamOnAndComesOutAtRapid) {
  const auto segs = segments("M3 S80\nG99 G86 X20 Y30 Z1 R2 P0.4 F300\nX25\n");
  ASSERT_EQ(kinds(segs), "rrfdrrfdr");  // the second hole: over it at R (G99), no move down
  EXPECT_EQ(segs[2].laser, LaserMode::Constant);
  EXPECT_DOUBLE_EQ(segs[3].dwell_s, 0.4);
  EXPECT_EQ(segs[4].laser, LaserMode::Off);
  EXPECT_DOUBLE_EQ(segs[4].end[2], 2.0);  // G99: back to R
  EXPECT_DOUBLE_EQ(segs[8].end[0], 25.0);
  const Diagnostic d = expect_error("G86 X20 Y30 Z1 R2 P0.4 F300\n", ErrorCode::GcodeUnsupported, 1, 1);
  EXPECT_MENTIONS(d, "M3 or M4 before G86");
  expect_error("M3 S80\nG86 X20 Y30 Z1 R2 F300\n", ErrorCode::GcodeMissingWord, 2, 1);  // P
}

TEST(CannedCycles, G83PecksBackToRAndG73BreaksByAClearance) {
  // R2 to Z0 in pecks of 0.8: 1.2, 0.4, then 0; G83 back to R between them
  // and down to 0.254 above the last depth
  auto segs = segments("G83 X20 Y30 Z0 R2 Q0.8 F300\n");
  ASSERT_EQ(kinds(segs), "rrfrrfrrfr");
  EXPECT_NEAR(segs[2].end[2], 1.2, 1e-12);
  EXPECT_NEAR(segs[3].end[2], 2.0, 1e-12);
  EXPECT_NEAR(segs[4].end[2], 1.454, 1e-12);
  EXPECT_NEAR(segs[5].end[2], 0.4, 1e-12);
  EXPECT_NEAR(segs[8].end[2], 0.0, 1e-12);
  segs = segments("G73 X20 Y30 Z0 R2 Q0.8 F300\n");
  ASSERT_EQ(kinds(segs), "rrfrfrfr");
  EXPECT_NEAR(segs[3].end[2], 1.454, 1e-12);
  EXPECT_NEAR(segs[5].end[2], 0.654, 1e-12);
}

TEST(CannedCycles, G85AndG89FeedOut) {
  auto segs = segments("G98 G85 X20 Y30 Z1 R2 F300\n");
  ASSERT_EQ(kinds(segs), "rrffr");
  EXPECT_DOUBLE_EQ(segs[3].end[2], 2.0);
  EXPECT_DOUBLE_EQ(segs[4].end[2], 10.0);
  segs = segments("G98 G89 X20 Y30 Z1 R2 P0.5 F300\n");  // G89 feeds out to the clear height
  ASSERT_EQ(kinds(segs), "rrfdf");
  EXPECT_DOUBLE_EQ(segs[4].end[2], 10.0);
}

TEST(CannedCycles, IncrementalRepeatsStepFromHoleToHole) {
  // G91: R from where Z stood (10 − 4 = 6), Z from R (6 − 3 = 3); L3 holes 5 apart
  const auto segs = segments("G91 G98 G81 X5 Y0 Z-3 R-4 L3 F300\n");
  ASSERT_EQ(segs.size(), 12u);
  for (int k = 0; k < 3; ++k) {
    EXPECT_POSE_NEAR(segs[4 * k].end, pose(15 + 5 * k, 10, 10), 1e-12);
    EXPECT_POSE_NEAR(segs[4 * k + 2].end, pose(15 + 5 * k, 10, 3), 1e-12);
  }
}

TEST(CannedCycles, RZPQAreStickyWithinACycleAndNeededAgainAfterIt) {
  auto segs = segments("G82 X20 Y30 Z1 R2 P0.4 F300\nX30\nG0 Z10\nG82 X40 Z1 R2 P0.1\n");
  ASSERT_EQ(kinds(segs), "rrfdrrfdrrrrfdr");
  EXPECT_DOUBLE_EQ(segs[7].dwell_s, 0.4);
  EXPECT_DOUBLE_EQ(segs[13].dwell_s, 0.1);
  Diagnostic d =
      expect_error("G81 X20 Y30 Z1 R2 F300\nG0 Z10\nG81 X40 Z1\n", ErrorCode::GcodeMissingWord, 3, 1);
  EXPECT_MENTIONS(d, "no R word");
  d = expect_error("G82 X20 Y30 Z1 R2 F300\n", ErrorCode::GcodeMissingWord, 1, 1);
  EXPECT_MENTIONS(d, "no P word");
  expect_error("G83 X20 Y30 Z1 R2 F300\n", ErrorCode::GcodeMissingWord, 1, 1);
}

TEST(CannedCycles, BadCyclesAreRefusedWhereTheyStand) {
  Diagnostic d = expect_error("G81 X20 Y30 Z3 R2 F300\n", ErrorCode::GcodeBadValue, 1, 13);
  EXPECT_MENTIONS(d, "bottom Z is above the retract plane R");
  d = expect_error("G18\nG81 X20 Y30 Z1 R2 F300\n", ErrorCode::GcodeUnsupported, 2, 1);
  EXPECT_MENTIONS(d, "canned cycles in G17");
  expect_error("G81 X20 Y30 Z1 R2 A5 F300\n", ErrorCode::GcodeSyntax, 1, 19);
  expect_error("G93 G81 X20 Y30 Z1 R2 F3\n", ErrorCode::GcodeSyntax, 1, 5);
  expect_error("G81 X20 Y30 Z1 R2 L0 F300\n", ErrorCode::GcodeBadValue, 1, 19);
  d = expect_error("G83 X20 Y30 Z-400 R2 Q0.0001 F300\n", ErrorCode::GcodeBadValue, 1, 22);
  EXPECT_MENTIONS(d, "moves from one line");
  // beyond the travel: the bottom (the test machine's Z starts at 0)
  expect_error("G81 X20 Y30 Z-1 R2 F300\n", ErrorCode::GcodeBeyondTravel, 1, 13);
}

// M0 (M60, and M1 with the optional stop on) stops the program after its
// line's motion: a two-period dwell, beam off, that the RT holds on.
TEST(ProgramPause, M0PausesAfterItsLinesMotionAndM1FollowsTheOptionalStop) {
  auto segs = segments("M3 S50\nG1 X20 F600 M0\nG1 X30\nM1\nM60\n");
  ASSERT_EQ(kinds(segs), "fdfdd");
  EXPECT_TRUE(segs[1].pause);
  EXPECT_EQ(segs[1].laser, LaserMode::Off);
  EXPECT_POSE_NEAR(segs[1].end, pose(20, 10, 10), 1e-12);
  EXPECT_DOUBLE_EQ(segs[1].dwell_s, 2.0 * test::test_machine().period_s());
  EXPECT_FALSE(segs[0].pause);
  EXPECT_TRUE(segs[3].pause);
  EXPECT_TRUE(segs[4].pause);
  MachineConfig no_optional = test::test_machine();
  no_optional.optional_stop = false;
  segs = segments("G1 X20 F600\nM1\nG1 X30\n", start_at(), no_optional);
  EXPECT_EQ(kinds(segs), "ff");
  const Diagnostic d = expect_error("M0 M2\n", ErrorCode::GcodeModalConflict, 1, 4);
  EXPECT_MENTIONS(d, "stopping");
}

// `$0` selects the spindle, the laser here: M3 $0 S… as posts write it.
TEST(SpindleSelector, DollarZeroIsTheLaserAnyOtherIsAnError) {
  const auto segs = segments("M3 $0 S40\nG1 X20 F600\nM5 $-1\n");
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_EQ(segs[0].laser, LaserMode::Constant);
  EXPECT_DOUBLE_EQ(segs[0].power_pct, 40.0);
  const Diagnostic d = expect_error("M3 $1 S40\n", ErrorCode::GcodeBadValue, 1, 4);
  EXPECT_MENTIONS(d, "one laser, spindle $0");
}

TEST(CannedCycles, G80WithAMoveOnItsLineIsPassedOverAsLinuxCNCDoes) {
  for (const char* line : {"G80 G0 X50 Y50\nX60\n", "G0 G80 X50 Y50\nX60\n"}) {
    const auto segs = segments(std::string("G81 X20 Y20 Z2 R5 F600\n") + line);
    ASSERT_GE(segs.size(), 2u) << line;
    EXPECT_EQ(segs[segs.size() - 2].kind, MotionKind::Rapid) << line;
    EXPECT_POSE_NEAR(segs[segs.size() - 2].end, pose(50, 50, 5), 1e-12) << line;  // Z at R (G99)
    EXPECT_POSE_NEAR(segs.back().end, pose(60, 50, 5), 1e-12) << line;            // G0, not a hole
  }
  expect_error("G0 G1 X5\n", ErrorCode::GcodeModalConflict, 1, 4);
}

}  // namespace
}  // namespace lcnc

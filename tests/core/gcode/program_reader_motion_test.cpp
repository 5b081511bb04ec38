// G0 G1 G4, units, distance modes, work offsets, feed modes: the segments
// the reader produces for straight moves and dwells.
#include <gtest/gtest.h>

#include "core/gcode/gcode_test_util.h"

namespace lcnc {
namespace {

using test::pose;
using test::segments;
using test::start_at;

TEST(ProgramReader, RapidIsRapidSegmentWithNoFeedAndLaserOff) {
  const auto segs = segments("M3 S50\nG0 X100 Y50\n");
  ASSERT_EQ(segs.size(), 1u);
  const Segment& s = segs[0];
  EXPECT_EQ(s.kind, MotionKind::Rapid);
  EXPECT_POSE_NEAR(s.start, pose(10, 10, 10), 1e-12);
  EXPECT_POSE_NEAR(s.end, pose(100, 50, 10), 1e-12);
  EXPECT_EQ(s.feed_mm_s, 0.0);
  EXPECT_EQ(s.duration_s, 0.0);
  EXPECT_EQ(s.laser, LaserMode::Off);  // never on during a rapid
  EXPECT_DOUBLE_EQ(s.power_pct, 50.0);
  EXPECT_EQ(s.line, 2u);
}

TEST(ProgramReader, LinearFeedIsMmPerMinuteOverSixty) {
  const auto segs = segments("G1 X100 Y10 F600\n");
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_EQ(segs[0].kind, MotionKind::Linear);
  EXPECT_POSE_NEAR(segs[0].end, pose(100, 10, 10), 1e-12);
  EXPECT_DOUBLE_EQ(segs[0].feed_mm_s, 10.0);
  EXPECT_EQ(segs[0].duration_s, 0.0);
  EXPECT_EQ(segs[0].line, 1u);
}

TEST(ProgramReader, InitialModesAreExactPathLaserOffGasOff) {
  const auto segs = segments("G1 X20 F600\n");
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_EQ(segs[0].path_mode, PathMode::ExactPath);
  EXPECT_EQ(segs[0].blend_tolerance_mm, 0.0);
  EXPECT_EQ(segs[0].laser, LaserMode::Off);
  EXPECT_EQ(segs[0].power_pct, 0.0);
  EXPECT_FALSE(segs[0].mist);
  EXPECT_FALSE(segs[0].flood);
  EXPECT_EQ(segs[0].plane, Plane::XY);
}

TEST(ProgramReader, AxisWordsAloneUseTheModalMotion) {
  const auto segs = segments("G1 X20 F600\nY30\nX40 Y40\nG0 Z50\nX60\n");
  ASSERT_EQ(segs.size(), 5u);
  EXPECT_EQ(segs[1].kind, MotionKind::Linear);
  EXPECT_POSE_NEAR(segs[1].end, pose(20, 30, 10), 1e-12);
  EXPECT_EQ(segs[1].line, 2u);
  EXPECT_EQ(segs[2].kind, MotionKind::Linear);
  EXPECT_POSE_NEAR(segs[2].end, pose(40, 40, 10), 1e-12);
  EXPECT_DOUBLE_EQ(segs[2].feed_mm_s, 10.0);  // F persists
  EXPECT_EQ(segs[3].kind, MotionKind::Rapid);
  EXPECT_EQ(segs[4].kind, MotionKind::Rapid);
  EXPECT_POSE_NEAR(segs[4].end, pose(60, 40, 50), 1e-12);
  EXPECT_EQ(segs[4].start, segs[3].end);
}

TEST(ProgramReader, MotionCodeWithoutAxesOnlySetsTheMode) {
  const auto segs = segments("G1 F600\nX20\n");
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_EQ(segs[0].kind, MotionKind::Linear);
  EXPECT_EQ(segs[0].line, 2u);
}

TEST(ProgramReader, MoveToWhereTheMachineIsProducesNoSegment) {
  const auto segs = segments("G1 X10 Y10 F600\nX20\n");
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_EQ(segs[0].line, 2u);
}

TEST(ProgramReader, InchesConvertLengthsAndFeedButNotRotaryAxes) {
  const auto segs = segments("G20 G1 X1 Y2 Z0.5 A10 F10\n");
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_POSE_NEAR(segs[0].end, pose(25.4, 50.8, 12.7, 10), 1e-12);
  EXPECT_DOUBLE_EQ(segs[0].feed_mm_s, 10 * 25.4 / 60.0);
}

TEST(ProgramReader, MillimetresAfterInches) {
  const auto segs = segments("G20 G0 X1\nG21 G0 X1\n");
  ASSERT_EQ(segs.size(), 2u);
  EXPECT_DOUBLE_EQ(segs[0].end[0], 25.4);
  EXPECT_DOUBLE_EQ(segs[1].end[0], 1.0);
}

TEST(ProgramReader, FeedKeepsItsSpeedWhenUnitsChangeLater) {
  // F10 read in inches is 254 mm/min; switching to G21 does not rescale it.
  const auto segs = segments("G20 F10\nG21 G1 X20\n");
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_DOUBLE_EQ(segs[0].feed_mm_s, 254.0 / 60.0);
}

TEST(ProgramReader, PureRotaryFeedIsDegreesPerMinute) {
  const auto segs = segments("G1 A30 F120\nG20 A40 F120\n");
  ASSERT_EQ(segs.size(), 2u);
  EXPECT_DOUBLE_EQ(segs[0].feed_mm_s, 2.0);  // deg/s
  EXPECT_DOUBLE_EQ(segs[1].feed_mm_s, 2.0);  // not scaled by 25.4 in G20
  EXPECT_DOUBLE_EQ(segs[1].end[3], 40.0);
}

TEST(ProgramReader, LinearAndRotaryMoveFeedsTheLinearPath) {
  const auto segs = segments("G1 X20 A30 F600\n");
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_DOUBLE_EQ(segs[0].feed_mm_s, 10.0);
}

TEST(ProgramReader, IncrementalMovesAddToThePosition) {
  const auto segs = segments("G91 G1 X5 Y-2 F600\nX5\nG90 X100\n");
  ASSERT_EQ(segs.size(), 3u);
  EXPECT_POSE_NEAR(segs[0].end, pose(15, 8, 10), 1e-12);
  EXPECT_POSE_NEAR(segs[1].end, pose(20, 8, 10), 1e-12);
  EXPECT_POSE_NEAR(segs[2].end, pose(100, 8, 10), 1e-12);
}

TEST(ProgramReader, IncrementalInchesScaleTheIncrement) {
  const auto segs = segments("G20 G91 G0 X1\n");
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_DOUBLE_EQ(segs[0].end[0], 10 + 25.4);
}

TEST(ProgramReader, WorkOffsetsMapProgramToMachine) {
  const auto segs = segments("G0 X20\nG55 X10\nG56 X10 Y10 Z10 A10\nG54 X10 Y10 Z10 A10\n");
  ASSERT_EQ(segs.size(), 4u);
  EXPECT_DOUBLE_EQ(segs[0].end[0], 20.0);                       // G54 default: zero offset
  EXPECT_DOUBLE_EQ(segs[1].end[0], 510.0);                      // G55: X+500
  EXPECT_POSE_NEAR(segs[2].end, pose(110, 60, 30, 15), 1e-12);  // G56
  EXPECT_POSE_NEAR(segs[3].end, pose(10, 10, 10, 10), 1e-12);
}

TEST(ProgramReader, WorkOffsetDoesNotApplyToIncrements) {
  const auto segs = segments("G55 G91 G0 X5\n");
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_DOUBLE_EQ(segs[0].end[0], 15.0);
}

TEST(ProgramReader, ContinuousRotaryAxisHasNoTravelLimit) {
  const auto segs = segments("G91 G0 C720\nG90 G0 C-30\n");
  ASSERT_EQ(segs.size(), 2u);
  EXPECT_DOUBLE_EQ(segs[0].end[5], 720.0);
  EXPECT_DOUBLE_EQ(segs[1].end[5], 690.0);  // -30 = 330 (mod 360): 30 back from 720
}

// G90 on a continuous rotary axis names a position modulo 360; the axis takes
// the shorter turn to it. The old reading took C 333 -> 10 the long way, -323.
TEST(ProgramReader, AbsoluteMoveOnAContinuousAxisTakesTheShorterTurn) {
  std::string program = "G1 F600";
  for (int k = 0; k <= 12; ++k)
    program += "\nX" + std::to_string(11 + k) + " C" + std::to_string((37 * k) % 360);
  const auto segs = segments(program + "\n");
  ASSERT_EQ(segs.size(), 13u);
  for (std::size_t i = 1; i < segs.size(); ++i) {
    EXPECT_NEAR(segs[i].end[5] - segs[i].start[5], 37.0, 1e-9) << "move " << i;
  }
  EXPECT_NEAR(segs.back().end[5], 444.0, 1e-9);  // 12 x 37, shown as 84
  EXPECT_DOUBLE_EQ(segs[0].end[5], 0.0);         // C 0 -> 0: X alone moves
}

TEST(ProgramReader, ShorterTurnCountsFromWhereTheMachineStands) {
  ReaderOptions o = start_at();
  o.start[5] = 350.0 + 720.0;  // two turns and 350
  const auto segs = segments("G0 C10\nG0 C190\nG0 C-170\nG91 C-322\n", o);
  ASSERT_EQ(segs.size(), 3u);                         // C-170 is where C190 left it: no motion
  EXPECT_NEAR(segs[0].end[5], 1090.0, 1e-9);          // +20, not -340
  EXPECT_NEAR(segs[1].end[5], 1270.0, 1e-9);          // a half turn: the positive way
  EXPECT_NEAR(segs[2].end[5], 1270.0 - 322.0, 1e-9);  // G91 turns by what it says
}

TEST(ProgramReader, AxisWithTravelLimitsIsNotWrapped) {
  const auto segs = segments("G0 A80\nG0 A-80\n");
  ASSERT_EQ(segs.size(), 2u);
  EXPECT_DOUBLE_EQ(segs[1].end[3], -80.0);  // a tilt axis goes where it is told
}

TEST(ProgramReader, TravelToleranceIsOneNanometre) {
  EXPECT_EQ(segments("G0 X1000.0000000001 Y0\n").size(), 1u);
}

TEST(ProgramReader, InverseTimeDurationIsSixtyOverF) {
  const auto segs = segments("G93 G1 X20 F2\nX40 F0.5\n");
  ASSERT_EQ(segs.size(), 2u);
  EXPECT_DOUBLE_EQ(segs[0].duration_s, 30.0);
  EXPECT_DOUBLE_EQ(segs[0].feed_mm_s, 10.0 / 30.0);
  EXPECT_DOUBLE_EQ(segs[1].duration_s, 120.0);
  EXPECT_DOUBLE_EQ(segs[1].feed_mm_s, 20.0 / 120.0);
}

TEST(ProgramReader, InverseTimeRapidNeedsNoF) {
  const auto segs = segments("G93\nG0 X50\n");
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_EQ(segs[0].kind, MotionKind::Rapid);
  EXPECT_EQ(segs[0].duration_s, 0.0);
}

TEST(ProgramReader, BackToUnitsPerMinuteClearsDuration) {
  const auto segs = segments("G93 G1 X20 F2\nG94 G1 X30 F600\n");
  ASSERT_EQ(segs.size(), 2u);
  EXPECT_EQ(segs[1].duration_s, 0.0);
  EXPECT_DOUBLE_EQ(segs[1].feed_mm_s, 10.0);
}

TEST(ProgramReader, DwellHoldsPositionForPSeconds) {
  const auto segs = segments("G0 X20\nM3 S40\nG4 P0.5\n");
  ASSERT_EQ(segs.size(), 2u);
  const Segment& d = segs[1];
  EXPECT_EQ(d.kind, MotionKind::Dwell);
  EXPECT_POSE_NEAR(d.start, pose(20, 10, 10), 1e-12);
  EXPECT_EQ(d.start, d.end);
  EXPECT_DOUBLE_EQ(d.dwell_s, 0.5);
  EXPECT_EQ(d.feed_mm_s, 0.0);
  EXPECT_EQ(d.laser, LaserMode::Constant);  // M3 + G4: percussion drilling
  EXPECT_DOUBLE_EQ(d.power_pct, 40.0);
  EXPECT_EQ(d.line, 3u);
}

TEST(ProgramReader, DwellRunsBeforeTheMotionOfItsBlock) {
  const auto segs = segments("G1 F600\nG4 P1 X20\n");
  ASSERT_EQ(segs.size(), 2u);
  EXPECT_EQ(segs[0].kind, MotionKind::Dwell);
  EXPECT_POSE_NEAR(segs[0].end, pose(10, 10, 10), 1e-12);
  EXPECT_EQ(segs[1].kind, MotionKind::Linear);
  EXPECT_POSE_NEAR(segs[1].end, pose(20, 10, 10), 1e-12);
  EXPECT_EQ(segs[1].line, 2u);
}

TEST(ProgramReader, DwellIsNotScaledByInches) {
  const auto segs = segments("G20 G4 P2\n");
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_DOUBLE_EQ(segs[0].dwell_s, 2.0);
}

TEST(ProgramReader, ModalStatePersistsAcrossLines) {
  const auto segs = segments(
      "G20 G91 G55 G64 P0.001 M3 S30 M8 G1 X1 F10\n"
      "Y1\n"
      "(nothing modal changes here)\n"
      "X-1 Y-1\n");
  ASSERT_EQ(segs.size(), 3u);
  for (const Segment& s : segs) {
    EXPECT_EQ(s.kind, MotionKind::Linear);
    EXPECT_EQ(s.path_mode, PathMode::Blend);
    EXPECT_DOUBLE_EQ(s.blend_tolerance_mm, 0.0254);
    EXPECT_EQ(s.laser, LaserMode::Constant);
    EXPECT_DOUBLE_EQ(s.power_pct, 30.0);
    EXPECT_TRUE(s.flood);
    EXPECT_FALSE(s.mist);
    EXPECT_DOUBLE_EQ(s.feed_mm_s, 254.0 / 60.0);
  }
  // Incremental inches; the G55 offset does not apply to increments.
  EXPECT_POSE_NEAR(segs[0].end, pose(35.4, 10, 10), 1e-12);
  EXPECT_POSE_NEAR(segs[1].end, pose(35.4, 35.4, 10), 1e-12);
  EXPECT_POSE_NEAR(segs[2].end, pose(10, 10, 10), 1e-12);
  EXPECT_EQ(segs[2].line, 4u);
}

}  // namespace
}  // namespace lcnc

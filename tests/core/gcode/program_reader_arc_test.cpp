// G2/G3: centre (I J K, G90.1/G91.1, R of both signs), orientation in the
// three planes, full circles, helices with P turns, inches and offsets.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "core/gcode/gcode_test_util.h"
#include "gcode/arc_geometry.h"

namespace lcnc {
namespace {

using test::expect_error;
using test::pose;
using test::segments;
using test::start_at;

constexpr double kPiProgramReaderArc = std::numbers::pi;

TEST(ProgramReader, G17ClockwiseQuarterCircleFromIJ) {
  const auto segs = segments("G2 X110 Y90 I0 J-10 F600\n", start_at(100, 100, 10));
  ASSERT_EQ(segs.size(), 1u);
  const Segment& s = segs[0];
  EXPECT_EQ(s.kind, MotionKind::Arc);
  EXPECT_EQ(s.plane, Plane::XY);
  EXPECT_TRUE(s.clockwise);
  EXPECT_EQ(s.extra_turns, 0u);
  EXPECT_POSE_NEAR(s.start, pose(100, 100, 10), 1e-12);
  EXPECT_POSE_NEAR(s.end, pose(110, 90, 10), 1e-12);
  EXPECT_VEC3_NEAR(s.center, Vec3(100, 90, 10), 1e-12);
  EXPECT_NEAR(gcode::arc_sweep_rad(s), kPiProgramReaderArc / 2, 1e-12);
  EXPECT_DOUBLE_EQ(s.feed_mm_s, 10.0);
  EXPECT_EQ(s.line, 1u);
}

TEST(ProgramReader, G17CounterClockwiseGoesTheLongWayBetweenTheSamePoints) {
  const auto segs = segments("G3 X110 Y90 J-10 F600\n", start_at(100, 100, 10));
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_FALSE(segs[0].clockwise);
  EXPECT_NEAR(gcode::arc_sweep_rad(segs[0]), 1.5 * kPiProgramReaderArc, 1e-12);
}

TEST(ProgramReader, G18ClockwiseQuarterCircleSeenFromPlusY) {
  // G18: (first, second, normal) = (Z, X, Y); I is X's centre offset, K Z's.
  // From X20 Z10 about X10 Z10, clockwise seen from +Y ends at X10 Z20.
  const auto segs = segments("G18 G2 X10 Z20 I-10 K0 F600\n", start_at(20, 10, 10));
  ASSERT_EQ(segs.size(), 1u);
  const Segment& s = segs[0];
  EXPECT_EQ(s.plane, Plane::ZX);
  EXPECT_TRUE(s.clockwise);
  EXPECT_POSE_NEAR(s.end, pose(10, 10, 20), 1e-12);
  EXPECT_VEC3_NEAR(s.center, Vec3(10, 10, 10), 1e-12);
  EXPECT_NEAR(gcode::arc_sweep_rad(s), kPiProgramReaderArc / 2, 1e-12);
  // The clockwise quarter passes no extreme point: X stays within [10, 20].
  Vec3 lo, hi;
  gcode::arc_bounds(s, lo, hi);
  EXPECT_NEAR(lo[0], 10, 1e-12);
  EXPECT_NEAR(hi[0], 20, 1e-12);
  EXPECT_NEAR(hi[2], 20, 1e-12);
}

TEST(ProgramReader, G18CounterClockwiseSameEndGoesThreeQuarters) {
  const auto segs = segments("G18 G3 X10 Z20 I-10 F600\n", start_at(20, 10, 10));
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_FALSE(segs[0].clockwise);
  EXPECT_NEAR(gcode::arc_sweep_rad(segs[0]), 1.5 * kPiProgramReaderArc, 1e-12);
}

TEST(ProgramReader, G19CounterClockwiseQuarterCircleSeenFromPlusX) {
  // G19: (Y, Z, X); J is Y's centre offset, K Z's. From Y20 Z10 about Y20 Z20,
  // counter-clockwise seen from +X ends at Y30 Z20.
  const auto segs = segments("G19 G3 Y30 Z20 J0 K10 F600\n", start_at(10, 20, 10));
  ASSERT_EQ(segs.size(), 1u);
  const Segment& s = segs[0];
  EXPECT_EQ(s.plane, Plane::YZ);
  EXPECT_FALSE(s.clockwise);
  EXPECT_VEC3_NEAR(s.center, Vec3(10, 20, 20), 1e-12);
  EXPECT_NEAR(gcode::arc_sweep_rad(s), kPiProgramReaderArc / 2, 1e-12);
}

TEST(ProgramReader, FullCircleWhenIJKArcEndsAtItsStart) {
  const auto segs = segments("G2 X100 Y100 I10 F600\n", start_at(100, 100, 10));
  ASSERT_EQ(segs.size(), 1u);
  const Segment& s = segs[0];
  EXPECT_EQ(s.start, s.end);
  EXPECT_VEC3_NEAR(s.center, Vec3(110, 100, 10), 1e-12);
  EXPECT_EQ(s.extra_turns, 0u);
  EXPECT_NEAR(gcode::arc_sweep_rad(s), 2 * kPiProgramReaderArc, 1e-12);
  EXPECT_NEAR(gcode::arc_length_mm(s), 2 * kPiProgramReaderArc * 10, 1e-9);
}

TEST(ProgramReader, HelixWithPTurnsAddsExtraTurnsAndMovesTheNormalAxis) {
  const auto segs = segments("G17 G3 X100 Y100 Z20 A30 I10 J0 P3 F600\n", start_at(100, 100, 10));
  ASSERT_EQ(segs.size(), 1u);
  const Segment& s = segs[0];
  EXPECT_EQ(s.extra_turns, 2u);
  EXPECT_FALSE(s.clockwise);
  EXPECT_POSE_NEAR(s.end, pose(100, 100, 20, 30), 1e-12);
  EXPECT_NEAR(s.center[2], 10.0, 1e-12);  // centre's normal coordinate: the start's
  EXPECT_NEAR(gcode::arc_sweep_rad(s), 6 * kPiProgramReaderArc, 1e-12);
  EXPECT_NEAR(gcode::arc_length_mm(s), std::hypot(10 * 6 * kPiProgramReaderArc, 10.0), 1e-9);
  EXPECT_DOUBLE_EQ(s.feed_mm_s, 10.0);
}

TEST(ProgramReader, ArcTurnsP1IsOneTurn) {
  const auto segs = segments("G2 X100 Y100 I10 P1 F600\n", start_at(100, 100, 10));
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_EQ(segs[0].extra_turns, 0u);
}

TEST(ProgramReader, RadiusFormPositiveIsTheShortArc) {
  // (100,100) -> (110,90), R10: centres (100,90) and (110,100).
  auto segs = segments("G2 X110 Y90 R10 F600\n", start_at(100, 100, 10));
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_VEC3_NEAR(segs[0].center, Vec3(100, 90, 10), 1e-9);
  EXPECT_NEAR(gcode::arc_sweep_rad(segs[0]), kPiProgramReaderArc / 2, 1e-9);

  segs = segments("G3 X110 Y90 R10 F600\n", start_at(100, 100, 10));
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_VEC3_NEAR(segs[0].center, Vec3(110, 100, 10), 1e-9);
  EXPECT_NEAR(gcode::arc_sweep_rad(segs[0]), kPiProgramReaderArc / 2, 1e-9);
}

TEST(ProgramReader, RadiusFormNegativeIsTheLongArc) {
  auto segs = segments("G2 X110 Y90 R-10 F600\n", start_at(100, 100, 10));
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_VEC3_NEAR(segs[0].center, Vec3(110, 100, 10), 1e-9);
  EXPECT_NEAR(gcode::arc_sweep_rad(segs[0]), 1.5 * kPiProgramReaderArc, 1e-9);

  segs = segments("G3 X110 Y90 R-10 F600\n", start_at(100, 100, 10));
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_VEC3_NEAR(segs[0].center, Vec3(100, 90, 10), 1e-9);
  EXPECT_NEAR(gcode::arc_sweep_rad(segs[0]), 1.5 * kPiProgramReaderArc, 1e-9);
}

TEST(ProgramReader, RadiusFormSemicircleAndTinyShortfallAreReachable) {
  auto segs = segments("G2 X120 Y100 R10 F600\n", start_at(100, 100, 10));
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_VEC3_NEAR(segs[0].center, Vec3(110, 100, 10), 1e-9);
  // LinuxCNC 2.9 (measured against its interpreter): half the chord may
  // exceed |R| by 0.00005 in = 0.00127 mm, in mm and inch programs alike;
  // the arc is then the half circle about the chord's midpoint
  segs = segments("G2 X120.0025 Y100 R10 F600\n", start_at(100, 100, 10));
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_VEC3_NEAR(segs[0].center, Vec3(110.00125, 100, 10), 1e-12);
  Diagnostic d =
      expect_error("G2 X120.0026 Y100 R10 F600\n", ErrorCode::GcodeArcRadius, 1, 19, start_at(100, 100, 10));
  EXPECT_MENTIONS(d, "less 0.00127 mm");
  segs = segments("G20 G2 X[100 / 25.4 + 2.00009] Y[100 / 25.4] R1 F6\n", start_at(100, 100, 10));
  ASSERT_EQ(segs.size(), 1u);
  expect_error("G20 G2 X[100 / 25.4 + 2.00011] Y[100 / 25.4] R1 F6\n", ErrorCode::GcodeArcRadius, 1, 46,
               start_at(100, 100, 10));
}

TEST(ProgramReader, RadiusFormInG18) {
  const auto segs = segments("G18 G2 X10 Z20 R10 F600\n", start_at(20, 10, 10));
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_VEC3_NEAR(segs[0].center, Vec3(10, 10, 10), 1e-9);
}

TEST(ProgramReader, AbsoluteArcCentreUsesProgramCoordinatesAndOffset) {
  auto segs = segments("G90.1 G2 X110 Y90 I100 J90 F600\n", start_at(100, 100, 10));
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_VEC3_NEAR(segs[0].center, Vec3(100, 90, 10), 1e-12);
  // G56 offset (100, 50, 20): program centre (0, 40) is machine (100, 90).
  segs = segments("G56 G90.1 G2 X10 Y40 I0 J40 F600\n", start_at(100, 100, 10));
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_POSE_NEAR(segs[0].end, pose(110, 90, 10), 1e-12);
  EXPECT_VEC3_NEAR(segs[0].center, Vec3(100, 90, 10), 1e-12);
  // Back to G91.1: centre from the start again.
  segs = segments("G90.1\nG91.1 G2 X110 Y90 I0 J-10 F600\n", start_at(100, 100, 10));
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_VEC3_NEAR(segs[0].center, Vec3(100, 90, 10), 1e-12);
}

TEST(ProgramReader, IncrementalArcEndWithIncrementalCentre) {
  const auto segs = segments("G91 G2 X10 Y-10 J-10 F600\n", start_at(100, 100, 10));
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_POSE_NEAR(segs[0].end, pose(110, 90, 10), 1e-12);
  EXPECT_VEC3_NEAR(segs[0].center, Vec3(100, 90, 10), 1e-12);
}

TEST(ProgramReader, ArcInInchesScalesEndCentreAndRadius) {
  auto segs = segments("G20 G2 X5 Y3 I0 J-1 F10\n", start_at(101.6, 101.6, 10));
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_POSE_NEAR(segs[0].end, pose(127, 76.2, 10), 1e-9);
  EXPECT_VEC3_NEAR(segs[0].center, Vec3(101.6, 76.2, 10), 1e-9);
  EXPECT_DOUBLE_EQ(segs[0].feed_mm_s, 254.0 / 60.0);
  segs = segments("G20 G2 X5 Y3 R1 F10\n", start_at(101.6, 101.6, 10));
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_VEC3_NEAR(segs[0].center, Vec3(101.6, 76.2, 10), 1e-9);
}

TEST(ProgramReader, SmallRadiusMismatchIsAccepted) {
  // 10.001 to the start, ~10.0000001 to the end: 0.001 mm apart (< 0.028).
  EXPECT_EQ(segments("G2 X110 Y90 J-10.001 F600\n", start_at(100, 100, 10)).size(), 1u);
}

// LinuxCNC 2.9 (measured with its interpreter): radii 5 and 5.028 mm are
// accepted, 5 and 5.029 refused (2·√2·0.01 mm = 0.0283 mm); in inches 1 and
// 1.0028 accepted, 1 and 1.0029 refused (2·√2·0.001 in). The arc keeps its
// programmed centre and end (a spiral between the two radii).
TEST(ProgramReader, ArcRadiiMayDifferByLinuxCncsCentreTolerance) {
  auto segs = segments("G3 X110.028 Y100 I5 J0 F600\n", start_at(100, 100, 10));
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_POSE_NEAR(segs[0].end, pose(110.028, 100, 10), 1e-12);
  EXPECT_VEC3_NEAR(segs[0].center, Vec3(105, 100, 10), 1e-12);
  Diagnostic d =
      expect_error("G3 X110.029 Y100 I5 J0 F600\n", ErrorCode::GcodeArcRadius, 1, 18, start_at(100, 100, 10));
  EXPECT_MENTIONS(d, "within 0.0282843 mm");
  segs = segments("G20 G3 X5.0028 Y3 I1 J0 F10\n", start_at(76.2, 76.2, 10));
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_POSE_NEAR(segs[0].end, pose(5.0028 * 25.4, 76.2, 10), 1e-9);
  d = expect_error("G20 G3 X5.0029 Y3 I1 J0 F10\n", ErrorCode::GcodeArcRadius, 1, 19,
                   start_at(76.2, 76.2, 10));
  EXPECT_MENTIONS(d, "radius 1 in to the start");
  EXPECT_MENTIONS(d, "within 0.00282843 in");
}

TEST(ProgramReader, LargeArcWithinRelativeRadiusToleranceIsAccepted) {
  // Radius 400 to the start, 400.1 to the end: 0.1 mm > 0.028 mm but only
  // 0.025 % (< 0.1 %) and below the 2.83 mm hard limit: LinuxCNC accepts it.
  const double a = 175.0 * kPiProgramReaderArc / 180.0;
  char prog[128];
  std::snprintf(prog, sizeof prog, "G2 X%.6f Y%.6f I400 J0 F600\n", 500 + 400.1 * std::cos(a),
                200 + 400.1 * std::sin(a));
  const auto segs = segments(prog, start_at(100, 200, 10));
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_VEC3_NEAR(segs[0].center, Vec3(500, 200, 10), 1e-12);
}

TEST(ProgramReader, ArcModalMotionContinuesWithAxisWords) {
  const auto segs = segments("G2 X110 Y90 J-10 F600\nX100 Y80 I-10\n", start_at(100, 100, 10));
  ASSERT_EQ(segs.size(), 2u);
  EXPECT_EQ(segs[1].kind, MotionKind::Arc);
  EXPECT_TRUE(segs[1].clockwise);
  EXPECT_VEC3_NEAR(segs[1].center, Vec3(100, 90, 10), 1e-12);
}

TEST(ProgramReader, PlaneStaysSelectedAcrossLines) {
  const auto segs = segments("G18\nG2 X10 Z20 I-10 F600\nG17 G0 X20\n", start_at(20, 10, 10));
  ASSERT_EQ(segs.size(), 2u);
  EXPECT_EQ(segs[0].plane, Plane::ZX);
  EXPECT_EQ(segs[1].plane, Plane::XY);
}

}  // namespace
}  // namespace lcnc

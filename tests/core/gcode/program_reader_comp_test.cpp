// Cutter (kerf) compensation G40 G41 G42 G41.1 G42.1 by LinuxCNC's rules:
// the tool centre one radius beside the path, arcs round convex corners,
// moves cut short into concave ones, a clear error where the tool cannot
// fit. (tests/data/linuxcnc_compare/cutter_comp.ngc runs every kind of
// corner through LinuxCNC's own interpreter in the e2e comparison.)
#include <gtest/gtest.h>

#include <cmath>

#include "core/gcode/gcode_test_util.h"
#include "gcode/arc_geometry.h"
#include "machine/machine_config.h"

namespace lcnc {
namespace {

using test::expect_error;
using test::pose;
using test::segments;

MachineConfig tool_machine() {
  MachineConfig m = test::test_machine();
  ToolConfig t1;
  t1.number = 1;
  t1.diameter_mm = 0.2;  // a 0.2 mm kerf
  ToolConfig t2;
  t2.number = 2;
  t2.diameter_mm = 4.0;
  m.tools = {t1, t2};
  return m;
}

// Each segment starts where the one before ends: the planner sees one path.
void expect_continuous(const std::vector<Segment>& segs) {
  for (std::size_t i = 1; i < segs.size(); ++i) {
    EXPECT_POSE_NEAR(segs[i].start, segs[i - 1].end, 1e-12) << "segment " << i;
  }
}

// Distance from p to the outline of the square [lo, hi]².
double to_square(const Pose& p, double lo, double hi) {
  const double dx = std::max({lo - p[0], 0.0, p[0] - hi});
  const double dy = std::max({lo - p[1], 0.0, p[1] - hi});
  if (dx > 0.0 || dy > 0.0) return std::hypot(dx, dy);
  return std::min({p[0] - lo, hi - p[0], p[1] - lo, hi - p[1]});
}

TEST(CutterComp, AKerfOutsideASquareRoundsItsCornersAndKeepsHalfTheKerfAway) {
  // clockwise, the beam on the left: outside, 0.1 mm off the drawn square
  const auto segs =
      segments("G0 X90 Y90\nG41 D1\nG1 X100 Y100 F600\nY120\nX120\nY100\nX100\nG40\nG0 X90 Y90\n",
               test::start_at(), tool_machine());
  ASSERT_EQ(segs.size(), 10u);
  expect_continuous(segs);
  // the entry ends square to itself, one radius left of (100, 100); the next
  // line's offset crosses it there: it is cut short to that crossing
  EXPECT_POSE_NEAR(segs[1].end, pose(99.9, 100.0 + 0.1 * std::tan(std::numbers::pi / 8), 10), 1e-12);
  EXPECT_EQ(segs[1].line, 3u);
  EXPECT_POSE_NEAR(segs[2].end, pose(99.9, 120, 10), 1e-12);
  // each corner: an arc of the kerf radius about it, clockwise (tool left)
  for (std::size_t i : {3u, 5u, 7u}) {
    ASSERT_EQ(segs[i].kind, MotionKind::Arc) << i;
    EXPECT_TRUE(segs[i].clockwise);
    EXPECT_NEAR((segs[i].end.head<2>() - segs[i].center.head<2>()).norm(), 0.1, 1e-12);
    EXPECT_NEAR(to_square(Pose(pose(segs[i].center[0], segs[i].center[1], 10)), 100, 120), 0.0, 1e-12);
  }
  EXPECT_EQ(segs[3].line, 5u);  // the corner arc belongs to the move after it
  EXPECT_VEC3_NEAR(segs[3].center, Vec3(100, 120, 10), 1e-12);
  // every move end on the cut is 0.1 mm outside the square
  for (std::size_t i = 2; i <= 8; ++i) {
    EXPECT_NEAR(to_square(segs[i].end, 100, 120), 0.1, 1e-12) << i;
    EXPECT_FALSE(segs[i].end[0] > 100 && segs[i].end[0] < 120 && segs[i].end[1] > 100 &&
                 segs[i].end[1] < 120);
  }
  EXPECT_POSE_NEAR(segs[8].end, pose(100, 99.9, 10), 1e-12);
  // G40: the next move leaves the path from where the tool stands
  EXPECT_EQ(segs[9].kind, MotionKind::Rapid);
  EXPECT_POSE_NEAR(segs[9].start, pose(100, 99.9, 10), 1e-12);
  EXPECT_POSE_NEAR(segs[9].end, pose(90, 90, 10), 1e-12);
}

TEST(CutterComp, InsideASquareEveryCornerCutsTheMoveBeforeShort) {
  // counter-clockwise with the tool (4 mm) on the left: inside; the entry
  // (up, the tool left of it) turns right onto X: a convex corner, an arc
  const auto segs =
      segments("G0 X100 Y95\nG41.1 D4\nG1 X100 Y100 F600\nX140\nY130\nX100\nY100\nG40\nG0 X100 Y95\n");
  expect_continuous(segs);
  ASSERT_EQ(segs.size(), 8u);
  EXPECT_POSE_NEAR(segs[1].end, pose(98, 100, 10), 1e-12);
  EXPECT_EQ(segs[2].kind, MotionKind::Arc);
  EXPECT_POSE_NEAR(segs[2].end, pose(100, 102, 10), 1e-12);
  for (std::size_t i = 3; i < segs.size(); ++i) EXPECT_NE(segs[i].kind, MotionKind::Arc) << i;
  EXPECT_POSE_NEAR(segs[3].end, pose(138, 102, 10), 1e-12);  // cut 2 mm short of the corner
  EXPECT_POSE_NEAR(segs[4].end, pose(138, 128, 10), 1e-12);
  EXPECT_POSE_NEAR(segs[5].end, pose(102, 128, 10), 1e-12);
  EXPECT_POSE_NEAR(segs[6].end, pose(102, 100, 10), 1e-12);  // the last: held to G40, as is
  // G41.1 D-4: a negative diameter is the other side: G42.1 D4
  const auto right = segments("G0 X100 Y95\nG42.1 D4\nG1 X100 Y100 F600\nX140\nG40\n");
  const auto neg = segments("G0 X100 Y95\nG41.1 D-4\nG1 X100 Y100 F600\nX140\nG40\n");
  ASSERT_EQ(right.size(), neg.size());
  for (std::size_t i = 0; i < right.size(); ++i) EXPECT_POSE_NEAR(right[i].end, neg[i].end, 1e-12);
  EXPECT_NEAR(right.back().end[1], 98.0, 1e-12);  // right of +X: below
}

TEST(CutterComp, ZMovesAndDwellsWaitWithTheMoveBeforeThemAndGoWithIt) {
  const auto segs =
      segments("G0 X100 Y95\nG41.1 D4\nG1 X100 Y100 F600\nX140\nZ5\nG4 P0.5\nY130\nG40\nG0 X100\n");
  expect_continuous(segs);
  ASSERT_EQ(segs.size(), 8u);
  EXPECT_EQ(segs[3].line, 4u);
  EXPECT_POSE_NEAR(segs[3].end, pose(138, 102, 10), 1e-12);  // cut short by the Y line after
  EXPECT_EQ(segs[4].line, 5u);                               // Z at the cut-short end
  EXPECT_POSE_NEAR(segs[4].end, pose(138, 102, 5), 1e-12);
  EXPECT_EQ(segs[5].kind, MotionKind::Dwell);  // then the dwell, there
  EXPECT_POSE_NEAR(segs[5].start, pose(138, 102, 5), 1e-12);
  EXPECT_EQ(segs[6].line, 7u);
  EXPECT_POSE_NEAR(segs[6].end, pose(138, 130, 5), 1e-12);  // held to G40, as is
}

TEST(CutterComp, ArcsAreOffsetAboutTheirCentreAndTheToolMustFitInside) {
  // a full circle of radius 10 from the inside with a 4 mm tool: radius 8,
  // the entry cut back to where it meets that circle
  const auto segs =
      segments("G0 X200 Y100\nG42.1 D4\nG1 X210 Y100 F600\nG2 X210 Y100 I-10 J0\nG40\nG0 X200 Y100\n");
  expect_continuous(segs);
  ASSERT_EQ(segs.size(), 4u);
  const Segment& circle = segs[2];
  ASSERT_EQ(circle.kind, MotionKind::Arc);
  EXPECT_EQ(circle.line, 4u);
  EXPECT_TRUE(circle.clockwise);
  EXPECT_VEC3_NEAR(circle.center, Vec3(200, 100, 10), 1e-12);
  EXPECT_NEAR((circle.start.head<2>() - circle.center.head<2>()).norm(), 8.0, 1e-12);
  EXPECT_POSE_NEAR(circle.end, pose(208, 100, 10), 1e-12);
  EXPECT_NEAR(circle.start[1], 98.0, 1e-12);  // on the entry's offset line
  EXPECT_GT(gcode::arc_sweep_rad(circle), 1.9 * std::numbers::pi);
  // a 4 mm tool inside an arc of radius 1.5: an error at the arc
  const Diagnostic d = expect_error("G0 X200 Y95\nG41.1 D4\nG1 X200 Y100 F600\nG1 X210\nG3 X213 Y100 R1.5\n",
                                    ErrorCode::GcodeCutterComp, 5, 1);
  EXPECT_MENTIONS(d, "not larger than the tool radius");
}

TEST(CutterComp, ACornerTheToolCannotReachIsAnErrorNamingTheMove) {
  // a notch 1 mm wide for a 4 mm tool: the 1 mm line would run backwards
  const Diagnostic d = expect_error("G0 X100 Y95\nG41.1 D4\nG1 X100 Y100 F600\nX150\nY101\nX100\n",
                                    ErrorCode::GcodeCutterComp, 6, 1);
  EXPECT_MENTIONS(d, "straight move of line 5 runs into a concave corner");
  EXPECT_MENTIONS(d, "gouging");
  EXPECT_MENTIONS(d, "tool radius 2 mm");
}

// A notch 1.9 mm wide for a 2 mm kerf: the beam does not fit, however the
// notch's end is drawn — one move, or two to four collinear ones (before,
// split ends passed the corner check and the beam cut 0.1 mm into both
// walls). A slot whose mouth is narrower than the beam is refused though
// each of its corners fits; 2.1 mm wide, both pass.
TEST(CutterComp, ANotchOrAMouthNarrowerThanTheToolIsRefusedHoweverItsMovesAreSplit) {
  const std::string head = "G0 X95 Y110\nG41.1 D2\nG1 X100 Y100 F600\nX110\nY90\n";
  const std::string tail = "Y100\nX130\nG40\nG0 X135 Y110\n";
  for (const std::string bottom :
       {"X111.9\n", "X110.5\nX111.9\n", "X110.1\nX111.9\n", "X110.2\nX110.4\nX111.6\nX111.9\n",
        "X110.95\nX111.9\n", "X111.5\nX111.9\n"}) {
    const test::Run r = test::run(head + bottom + tail);
    ASSERT_EQ(r.last, ProgramReader::Next::Error) << bottom;
    EXPECT_EQ(r.error.code, ErrorCode::GcodeCutterComp) << r.error.to_string();
  }
  // the notch wide enough: the tool fits, split or not
  for (const std::string bottom : {"X112.1\n", "X111.05\nX112.1\n"}) {
    const auto segs = segments(head + bottom + "Y100\nX130\nG40\nG0 X135 Y110\n");
    EXPECT_FALSE(segs.empty());
  }
  // the mouth 1.9 mm wide, the slot under it 6 mm: no corner is too tight
  const std::string slot =
      "G0 X95 Y110\nG41.1 D2\nG1 X100 Y100 F600\nX110\nY95\nX108\nY85\n"
      "X114\nY95\nX111.9\nY100\nX130\nG40\nG0 X135 Y110\n";
  const test::Run r = test::run(slot);
  ASSERT_EQ(r.last, ProgramReader::Next::Error);
  EXPECT_EQ(r.error.code, ErrorCode::GcodeCutterComp);
  // found where the right wall of the mouth comes in reach of the path down
  // the left one (line 5, 0.9 mm from it)
  EXPECT_EQ(r.error.line, 10u) << r.error.to_string();
  EXPECT_MENTIONS(r.error,
                  "compensated path of line 5 comes within 0.9 mm of the programmed "
                  "path of line 10, nearer than the tool radius");
  std::string wide = slot;
  wide.replace(wide.find("X111.9"), 6, "X112.1");
  EXPECT_FALSE(segments(wide).empty());
}

TEST(CutterComp, TheEntryMoveMustBeLongerThanTheRadius) {
  const Diagnostic d =
      expect_error("G0 X100 Y100\nG41.1 D4\nG1 X101 F600\n", ErrorCode::GcodeCutterComp, 3, 1);
  EXPECT_MENTIONS(d, "entry move is 1 mm long");
  // a Z move first is no entry either (LinuxCNC's rule)
  expect_error("G0 X100 Y100\nG41.1 D4\nG1 Z5 F600\n", ErrorCode::GcodeCutterComp, 3, 1);
}

TEST(CutterComp, StopsAndTheProgramsEndLetTheHeldMovesGo) {
  // M0: the move before it comes out before the pause, as it stands
  auto segs = segments("G0 X100 Y95\nG41.1 D2\nG1 X100 Y100 F600\nX150\nM0\nY130\nM2\n");
  expect_continuous(segs);
  ASSERT_GE(segs.size(), 6u);
  EXPECT_EQ(segs[3].line, 4u);
  EXPECT_POSE_NEAR(segs[3].end, pose(150, 101, 10), 1e-12);
  EXPECT_TRUE(segs[4].pause);
  EXPECT_EQ(segs[5].line, 6u);
  // no M2: the file's end does the same
  segs = segments("G0 X100 Y95\nG41.1 D2\nG1 X100 Y100 F600\nX150\n");
  ASSERT_EQ(segs.size(), 4u);
  EXPECT_POSE_NEAR(segs[3].end, pose(150, 101, 10), 1e-12);
}

TEST(CutterComp, TheRadiusComesFromTheToolTheDWordOrTheSpindleNames) {
  // T2 (4 mm) in the spindle: G41 alone takes it, G41 D1 tool 1 (0.2 mm)
  auto segs =
      segments("T2 M6\nG0 X100 Y95\nG41\nG1 X100 Y100 F600\nX150\nG40\n", test::start_at(), tool_machine());
  EXPECT_NEAR(segs.back().end[1], 102.0, 1e-12);
  segs = segments("T2 M6\nG0 X100 Y95\nG41 D1\nG1 X100 Y100 F600\nX150\nG40\n", test::start_at(),
                  tool_machine());
  EXPECT_NEAR(segs.back().end[1], 100.1, 1e-12);
  // no tool in the spindle: radius 0, the path as drawn
  segs = segments("G0 X100 Y95\nG41\nG1 X100 Y100 F600\nX150\nG40\n", test::start_at(), tool_machine());
  EXPECT_NEAR(segs.back().end[1], 100.0, 1e-12);
  // G41.1 D in inches
  segs = segments("G20\nG0 X4 Y4\nG41.1 D0.1\nG1 X4 Y5 F20\nX6\nG40\n");
  EXPECT_NEAR(segs.back().end[1], 127.0 + 1.27, 1e-9);
  expect_error("G41 D9\n", ErrorCode::GcodeNoSuchTool, 1, 5, test::start_at(), tool_machine());
}

TEST(CutterComp, WhatWouldMoveThePathUnderItIsRefused) {
  const std::string on = "G0 X100 Y95\nG41.1 D2\nG1 X100 Y100 F600\n";
  Diagnostic d =
      expect_error(on + "T1 M6\n", ErrorCode::GcodeModalConflict, 4, 4, test::start_at(), tool_machine());
  EXPECT_MENTIONS(d, "'M6' with cutter compensation on");
  EXPECT_MENTIONS(d, "expected G40");
  expect_error(on + "G55\n", ErrorCode::GcodeModalConflict, 4, 1);
  expect_error(on + "G18\n", ErrorCode::GcodeModalConflict, 4, 1);
  expect_error(on + "G43.1 Z1\n", ErrorCode::GcodeModalConflict, 4, 1);
  expect_error(on + "G92 X0\n", ErrorCode::GcodeModalConflict, 4, 1);
  expect_error(on + "G28\n", ErrorCode::GcodeModalConflict, 4, 1);
  expect_error(on + "G64 P0.1\n", ErrorCode::GcodeModalConflict, 4, 1);
  expect_error(on + "G81 X120 Y100 Z5 R8\n", ErrorCode::GcodeModalConflict, 4, 1);
  expect_error(on + "G41.1 D2\n", ErrorCode::GcodeModalConflict, 4, 1);
  // G40 first in the same block lets them run
  segments(on + "G40 G55 G0 X0\n");
  // the move leaving the path after G40 is straight
  d = expect_error(on + "X150\nG40\nG2 X160 Y100 R5\n", ErrorCode::GcodeCutterComp, 6, 1);
  EXPECT_MENTIONS(d, "just after G40");
  // the words and planes it takes
  d = expect_error("G1 X20 D1 F600\n", ErrorCode::GcodeUnsupported, 1, 8);
  EXPECT_MENTIONS(d, "with no G41, G42, G41.1 or G42.1 to use it");
  expect_error("G19 G41.1 D2\n", ErrorCode::GcodeUnsupported, 1, 5);
  expect_error("G41.1\n", ErrorCode::GcodeMissingWord, 1, 1);
  expect_error("G93 G41.1 D2\n", ErrorCode::GcodeUnsupported, 1, 5);
}

TEST(CutterComp, G91MovesAndMissingWordsCountFromTheProgrammedPoint) {
  // after the entry the tool stands 2 mm beside (100, 100); G91 X50 is from
  // (100, 100), and Y alone keeps the programmed X
  const auto segs = segments("G0 X100 Y95\nG41.1 D4\nG1 X100 Y100 F600\nG91 X50\nG90 Y130\nG40\n");
  ASSERT_EQ(segs.size(), 5u);
  EXPECT_POSE_NEAR(segs[3].end, pose(148, 102, 10), 1e-12);
  EXPECT_POSE_NEAR(segs[4].end, pose(148, 130, 10), 1e-12);
}

}  // namespace
}  // namespace lcnc

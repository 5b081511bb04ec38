// What the operator's controls ask of a reading (ReaderOptions): the modes
// an MDI command carries to the next, run from line, single block, dry run.
#include <gtest/gtest.h>

#include "core/gcode/gcode_test_util.h"

namespace lcnc {
namespace {

using test::pose;
using test::run;
using test::start_at;

ReaderModes modes_after(const std::string& text, ReaderOptions o = start_at()) {
  auto reader = ProgramReader::from_string(text, "mdi", test::test_machine(), o);
  Segment s;
  while (reader->next(s) == ProgramReader::Next::Segment) {
  }
  EXPECT_EQ(reader->error().message, "");
  return reader->modes();
}

TEST(ReaderModes, OneCommandsModesCarryToTheNext) {
  ReaderOptions o = start_at(10, 10, 10);
  const ReaderModes m = modes_after("G20 G91 G55 G64 P0.001 G1 X1 F20 S40\n", o);
  EXPECT_EQ(m.block, "G17 G20 G91 G91.1 G94 G55 G64 P0.001 F20 S40 G1");
  EXPECT_TRUE(m.inch);
  EXPECT_EQ(m.coord_system, 1);
  EXPECT_DOUBLE_EQ(m.offsets[0], 500.0);
  // the next command goes on in them: X1 is 1 inch further at 20 in/min, G1
  o.start = pose(10 + 25.4, 10, 10);
  o.modes = m.block;
  const test::Run r = run("X1\n", o);
  ASSERT_EQ(r.last, ProgramReader::Next::End) << r.error.message;
  ASSERT_EQ(r.segments.size(), 1u);
  EXPECT_EQ(r.segments[0].kind, MotionKind::Linear);
  EXPECT_NEAR(r.segments[0].end[0], 10 + 2 * 25.4, 1e-9);
  EXPECT_NEAR(r.segments[0].feed_mm_s, 20 * 25.4 / 60.0, 1e-9);
  EXPECT_NEAR(r.segments[0].blend_tolerance_mm, 0.0254, 1e-12);
}

TEST(ReaderModes, TheDefaultsReadBackAsTheDefaults) {
  const ReaderModes m = modes_after("");
  EXPECT_EQ(m.block, "G17 G21 G90 G91.1 G94 G54 G61");
  EXPECT_EQ(m.coord_system, 0);
  EXPECT_EQ(m.offsets, Pose::Zero());
}

TEST(ReaderModes, ModesThatMoveAreRefused) {
  ReaderOptions o = start_at();
  o.modes = "G0 X5";
  const test::Run r = run("G1 X20 F100\n", o);
  ASSERT_EQ(r.last, ProgramReader::Next::Error);
  EXPECT_MENTIONS(r.error, "the modes carried in from before");
  EXPECT_MENTIONS(r.error, "it moves");
}

TEST(ReaderModes, TouchOffMovesTheWorkOriginToTheMachine) {
  // G10 L20 P0: the current system's origin so that here reads X0 Y0
  const ReaderModes m = modes_after("G10 L20 P0 X0 Y5\n", start_at(120, 40, 10));
  EXPECT_DOUBLE_EQ(m.offsets[0], 120.0);
  EXPECT_DOUBLE_EQ(m.offsets[1], 35.0);
  EXPECT_DOUBLE_EQ(m.offsets[2], 0.0);
}

constexpr const char* kProgram =
    "G21 G90 G64 P0.01\n"  // 1
    "G0 X20 Y20 Z5\n"      // 2
    "F600 S50 M3\n"        // 3
    "G1 X40\n"             // 4
    "G1 Y40\n"             // 5
    "G0 Z30\n"             // 6
    "G0 X100 Y100\n"       // 7
    "G1 Z2 F300\n"         // 8
    "G1 X120\n"            // 9
    "M5 M2\n";             // 10

TEST(RunFromLine, ReadsTheBlocksBeforeAndApproachesSafely) {
  ReaderOptions o = start_at(0, 0, 10);
  o.start_line = 5;
  const test::Run r = run(kProgram, o);
  ASSERT_EQ(r.last, ProgramReader::Next::End) << r.error.message;
  ASSERT_GE(r.segments.size(), 3u);
  // approach: across at Z10 (higher than line 5's start Z5) to X40 Y20, then down
  const Segment& across = r.segments[0];
  EXPECT_EQ(across.kind, MotionKind::Rapid);
  EXPECT_EQ(across.laser, LaserMode::Off);
  EXPECT_EQ(across.start, pose(0, 0, 10));
  EXPECT_EQ(across.end, pose(40, 20, 10));
  const Segment& down = r.segments[1];
  EXPECT_EQ(down.kind, MotionKind::Rapid);
  EXPECT_EQ(down.end, pose(40, 20, 5));
  // then line 5 as the program would have it: its feed, its beam
  const Segment& first = r.segments[2];
  EXPECT_EQ(first.line, 5u);
  EXPECT_EQ(first.start, pose(40, 20, 5));
  EXPECT_EQ(first.end, pose(40, 40, 5));
  EXPECT_EQ(first.laser, LaserMode::Constant);
  EXPECT_NEAR(first.power_pct, 50.0, 1e-12);
  EXPECT_NEAR(first.feed_mm_s, 10.0, 1e-12);
  EXPECT_EQ(first.path_mode, PathMode::Blend);
  for (const Segment& s : r.segments) EXPECT_TRUE(s.line >= 5u) << s.line;
  // and on to the end
  EXPECT_EQ(r.segments.back().end, pose(120, 100, 2));
}

TEST(RunFromLine, RisesFirstWhenTheStartIsLower) {
  ReaderOptions o = start_at(0, 0, 1);
  o.start_line = 9;  // starts at X100 Y100 Z2 (after the G0 Z30 and the G1 Z2)
  const test::Run r = run(kProgram, o);
  ASSERT_EQ(r.last, ProgramReader::Next::End) << r.error.message;
  ASSERT_EQ(r.segments.size(), 3u);
  EXPECT_EQ(r.segments[0].end, pose(0, 0, 2));      // up
  EXPECT_EQ(r.segments[1].end, pose(100, 100, 2));  // across
  EXPECT_EQ(r.segments[2].line, 9u);
  EXPECT_NEAR(r.segments[2].feed_mm_s, 5.0, 1e-12);  // F300 of line 8 replayed
}

TEST(RunFromLine, ALinePastTheLastMoveIsAnError) {
  ReaderOptions o = start_at();
  o.start_line = 10;
  const test::Run r = run(kProgram, o);
  ASSERT_EQ(r.last, ProgramReader::Next::Error);
  EXPECT_EQ(r.error.line, 10u);
  EXPECT_MENTIONS(r.error, "run from line 10");
}

TEST(SingleBlock, PausesAfterEachBlocksMoves) {
  ReaderOptions o = start_at(0, 0, 10);
  o.single_block = true;
  const test::Run r = run("G0 X10\nG1 X20 F600\nG81 X30 Y0 Z1 R5\nG80\nM2\n", o);
  ASSERT_EQ(r.last, ProgramReader::Next::End) << r.error.message;
  // G0, pause, G1, pause, the cycle's moves (one block: no pause among them)
  std::vector<std::uint32_t> pauses;
  std::size_t cycle_moves = 0;
  for (const Segment& s : r.segments) {
    if (s.pause) pauses.push_back(s.line);
    if (s.line == 3 && !s.pause) ++cycle_moves;
  }
  EXPECT_EQ(pauses, (std::vector<std::uint32_t>{1, 2}));
  EXPECT_GE(cycle_moves, 3u);
  EXPECT_TRUE(r.segments[1].pause);
  EXPECT_EQ(r.segments[1].kind, MotionKind::Dwell);
  EXPECT_EQ(r.segments[1].end, pose(10, 0, 10));
  EXPECT_FALSE(r.segments.back().pause);  // the end needs none
}

TEST(DryRun, EveryMoveWithTheBeamOff) {
  ReaderOptions o = start_at(0, 0, 10);
  const std::string text = "G1 X10 F600 S80 M3\nG2 X20 I5\nG4 P0.5\nM5 M2\n";
  const test::Run lit = run(text, o);
  o.laser_off = true;
  const test::Run dry = run(text, o);
  ASSERT_EQ(dry.last, ProgramReader::Next::End) << dry.error.message;
  ASSERT_EQ(lit.segments.size(), dry.segments.size());
  bool any_lit = false;
  for (std::size_t i = 0; i < dry.segments.size(); ++i) {
    any_lit = any_lit || lit.segments[i].laser != LaserMode::Off;
    EXPECT_EQ(dry.segments[i].laser, LaserMode::Off);
    EXPECT_EQ(dry.segments[i].power_pct, 0.0);
    EXPECT_EQ(dry.segments[i].end, lit.segments[i].end);
    EXPECT_EQ(dry.segments[i].feed_mm_s, lit.segments[i].feed_mm_s);
  }
  EXPECT_TRUE(any_lit);
}

}  // namespace
}  // namespace lcnc

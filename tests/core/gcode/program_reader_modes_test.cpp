// Laser, assist gas, path control, program end, delimiters, block delete,
// comments and the lexical forms LinuxCNC accepts.
#include <gtest/gtest.h>

#include <cstdio>

#include "core/gcode/gcode_test_util.h"

namespace lcnc {
namespace {

using test::expect_error;
using test::pose;
using test::run;
using test::segments;
using test::start_at;
using test::test_machine;

TEST(ProgramReader, M3IsConstantPowerFromS) {
  const auto segs = segments("M3 S40\nG1 X20 F600\n");
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_EQ(segs[0].laser, LaserMode::Constant);
  EXPECT_DOUBLE_EQ(segs[0].power_pct, 40.0);
}

TEST(ProgramReader, M4IsDynamicPowerAndM5IsOff) {
  const auto segs = segments("M4 S25 G1 X20 F600\nM5 X30\n");
  ASSERT_EQ(segs.size(), 2u);
  EXPECT_EQ(segs[0].laser, LaserMode::Dynamic);
  EXPECT_DOUBLE_EQ(segs[0].power_pct, 25.0);
  EXPECT_EQ(segs[1].laser, LaserMode::Off);
  EXPECT_DOUBLE_EQ(segs[1].power_pct, 25.0);  // S stays programmed
}

TEST(ProgramReader, PowerIsSOverSMax) {
  MachineConfig m = test::test_machine();
  m.laser.s_max = 1000.0;
  const auto segs = segments("M3 S250 G1 X20 F600\nS1000 X30\n", start_at(), m);
  ASSERT_EQ(segs.size(), 2u);
  EXPECT_DOUBLE_EQ(segs[0].power_pct, 25.0);
  EXPECT_DOUBLE_EQ(segs[1].power_pct, 100.0);
}

TEST(ProgramReader, StateChangesBetweenMovesAddNoSegments) {
  const auto segs = segments(
      "G1 X20 F600 M3 S10\n"
      "S20\n"
      "(a comment)\n"
      "; another\n"
      "\n"
      "M4\n"
      "M8\n"
      "F1200\n"
      "G1 X30\n");
  ASSERT_EQ(segs.size(), 2u);  // the motion stream is unbroken
  EXPECT_EQ(segs[0].start, test::start_at().start);
  EXPECT_EQ(segs[1].start, segs[0].end);
  EXPECT_DOUBLE_EQ(segs[0].power_pct, 10.0);
  EXPECT_EQ(segs[0].laser, LaserMode::Constant);
  EXPECT_DOUBLE_EQ(segs[1].power_pct, 20.0);  // picks up the new S
  EXPECT_EQ(segs[1].laser, LaserMode::Dynamic);
  EXPECT_TRUE(segs[1].flood);
  EXPECT_DOUBLE_EQ(segs[1].feed_mm_s, 20.0);
  EXPECT_EQ(segs[1].line, 9u);
}

TEST(ProgramReader, M7MistM8FloodBothAllowedM9BothOff) {
  const auto segs = segments("M7 G1 X20 F600\nM8 X30\nM9 X40\nM7 M8 X50\n");
  ASSERT_EQ(segs.size(), 4u);
  EXPECT_TRUE(segs[0].mist);
  EXPECT_FALSE(segs[0].flood);
  EXPECT_TRUE(segs[1].mist);
  EXPECT_TRUE(segs[1].flood);
  EXPECT_FALSE(segs[2].mist);
  EXPECT_FALSE(segs[2].flood);
  EXPECT_TRUE(segs[3].mist);
  EXPECT_TRUE(segs[3].flood);
}

TEST(ProgramReader, G64WithoutPUsesTheMachinePathTolerance) {
  const auto segs = segments("G64 G1 X20 F600\n");
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_EQ(segs[0].path_mode, PathMode::Blend);
  EXPECT_DOUBLE_EQ(segs[0].blend_tolerance_mm, 0.01);
  EXPECT_DOUBLE_EQ(segs[0].naive_cam_tolerance_mm, 0.0);  // no Q: no line merging
}

TEST(ProgramReader, G64PAndQSetTheTolerances) {
  auto segs = segments("G64 P0.05 Q0.02\nG1 X20 F600\n");
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_EQ(segs[0].path_mode, PathMode::Blend);
  EXPECT_DOUBLE_EQ(segs[0].blend_tolerance_mm, 0.05);
  EXPECT_DOUBLE_EQ(segs[0].naive_cam_tolerance_mm, 0.02);
  segs = segments("G20 G64 P0.001 Q0.002\nG1 X1 F10\n");
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_DOUBLE_EQ(segs[0].blend_tolerance_mm, 0.0254);
  EXPECT_DOUBLE_EQ(segs[0].naive_cam_tolerance_mm, 0.0508);
}

// The machine's startup code runs before the program's first line: a CAM
// file that never writes G64 blends on a machine that starts in it, and the
// program's own G61 still asks for the exact path.
TEST(ProgramReader, StartupCodeSetsTheModesEveryProgramStartsIn) {
  MachineConfig m = test_machine();
  m.startup_code = "G64 P0.05 G91";
  auto segs = segments("G1 X5 F600\nG61 X5\n", start_at(), m);
  ASSERT_EQ(segs.size(), 2u);
  EXPECT_EQ(segs[0].path_mode, PathMode::Blend);
  EXPECT_DOUBLE_EQ(segs[0].blend_tolerance_mm, 0.05);
  EXPECT_DOUBLE_EQ(segs[0].end[0], 15.0);  // G91 from the startup code
  EXPECT_EQ(segs[1].path_mode, PathMode::ExactPath);
  m.startup_code = "G64";
  segs = segments("G1 X20 F600\n", start_at(), m);
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_DOUBLE_EQ(segs[0].blend_tolerance_mm, m.path_tolerance_mm);  // bare G64
  EXPECT_EQ(segs[0].path_mode, PathMode::Blend);
  // without one: G61, as RS274NGC
  EXPECT_EQ(segments("G1 X20 F600\n")[0].path_mode, PathMode::ExactPath);
}

// A startup code that bypassed the config's check (a config built in code)
// never moves the machine: the reader fails before the first line.
TEST(ProgramReader, AStartupCodeThatWouldMoveFailsTheReader) {
  MachineConfig m = test_machine();
  m.startup_code = "G1 X50 F600";
  const test::Run r = run("G1 X20\n", start_at(), m);
  EXPECT_EQ(r.last, ProgramReader::Next::Error);
  EXPECT_TRUE(r.segments.empty());
  EXPECT_EQ(r.error.code, ErrorCode::ConfigBadValue);
  EXPECT_NE(r.error.message.find("machine.startup_code"), std::string::npos) << r.error.to_string();
}

TEST(ProgramReader, G61AndG611AreExactPathAndExactStop) {
  const auto segs = segments("G64 P0.1 G1 X20 F600\nG61.1 X30\nG61 X40\n");
  ASSERT_EQ(segs.size(), 3u);
  EXPECT_EQ(segs[0].path_mode, PathMode::Blend);
  EXPECT_EQ(segs[1].path_mode, PathMode::ExactStop);
  EXPECT_EQ(segs[1].blend_tolerance_mm, 0.0);
  EXPECT_EQ(segs[2].path_mode, PathMode::ExactPath);
  EXPECT_EQ(segs[2].blend_tolerance_mm, 0.0);
}

TEST(ProgramReader, M2EndsTheProgramAndWarnsAboutLinesAfterIt) {
  const auto r = run("G1 X20 F600\nM2\n\n(comment)\nG1 X30\nG1 X40\n");
  EXPECT_EQ(r.last, ProgramReader::Next::End);
  ASSERT_EQ(r.segments.size(), 1u);
  ASSERT_EQ(r.warnings.size(), 1u);
  const Diagnostic& w = r.warnings[0];
  EXPECT_EQ(w.code, ErrorCode::GcodeLinesAfterEnd);
  EXPECT_EQ(w.line, 5u);
  EXPECT_EQ(w.col, 1u);
  EXPECT_NE(w.message.find("2 lines"), std::string::npos) << w.message;
  EXPECT_NE(w.message.find("M2 on line 2"), std::string::npos) << w.message;
  EXPECT_EQ(r.lines, 6u);
}

TEST(ProgramReader, M30OnAMotionLineMovesThenEnds) {
  const auto r = run("G1 X20 F600 M30\n   \n%\n");
  EXPECT_EQ(r.last, ProgramReader::Next::End);
  ASSERT_EQ(r.segments.size(), 1u);
  EXPECT_TRUE(r.warnings.empty());  // blank and '%' lines need no warning
}

TEST(ProgramReader, PercentDelimitsTheProgram) {
  const auto r = run("%\nG1 X20 F600\n%\nG1 X30\n");
  EXPECT_EQ(r.last, ProgramReader::Next::End);
  ASSERT_EQ(r.segments.size(), 1u);
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_EQ(r.warnings[0].line, 4u);
  EXPECT_NE(r.warnings[0].message.find("'%'"), std::string::npos);
}

TEST(ProgramReader, PercentLineMayCarryAComment) { EXPECT_EQ(segments("% (start)\nG0 X20\n").size(), 1u); }

// The safety header CAM posts write: the cancels have nothing to cancel.
TEST(ProgramReader, SafetyHeaderWithG40G49G80IsAccepted) {
  const auto segs = segments("G17 G21 G40 G49 G80 G90 G94 G54\nG1 X20 F600\n");
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_DOUBLE_EQ(segs[0].end[0], 20.0);
}

// G80 is of the motion group (LinuxCNC): it ends the motion mode in effect,
// and takes no axis words itself.
TEST(ProgramReader, G80CancelsTheMotionMode) {
  EXPECT_EQ(segments("G1 X20 F600\nG80\nG1 X30\n").size(), 2u);
  expect_error("G1 X10 F600\nG80\nX20\n", ErrorCode::GcodeNoMotionMode, 3, 1);
  const Diagnostic d = expect_error("G1 X10 F600\nG80 X20\n", ErrorCode::GcodeSyntax, 2, 5);
  EXPECT_MENTIONS(d, "G80");
  // with another motion code on its line G80 is passed over (LinuxCNC)
  const auto segs = segments("G1 G80 X20 F600\n");
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_EQ(segs[0].kind, MotionKind::Linear);
}

TEST(ProgramReader, BlockDeleteSkipsSlashLinesByDefault) {
  // LinuxCNC's default: a '/' line is not run
  auto segs = segments("/G1 X20 F600\nG1 X30 F600\n");
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_DOUBLE_EQ(segs[0].end[0], 30.0);
  EXPECT_EQ(segs[0].line, 2u);
  // the reader's switch off: the line runs
  ReaderOptions off = start_at();
  off.block_delete = false;
  segs = segments("/G1 X20 F600\nG1 X30 F600\n", off);
  ASSERT_EQ(segs.size(), 2u);
  EXPECT_DOUBLE_EQ(segs[0].end[0], 20.0);
  // the machine's switch off: the line runs, unless the reader says otherwise
  MachineConfig m = test::test_machine();
  m.block_delete = false;
  EXPECT_EQ(segments("/G1 X20 F600\nG1 X30 F600\n", start_at(), m).size(), 2u);
  ReaderOptions on = start_at();
  on.block_delete = true;
  EXPECT_EQ(segments("/G1 X20 F600\nG1 X30 F600\n", on, m).size(), 1u);
}

TEST(ProgramReader, CommentsAnywhereAreIgnored) {
  const auto segs = segments("(header) G1 (move) X20 (to x) F600 ; the rest (is ignored\n");
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_DOUBLE_EQ(segs[0].end[0], 20.0);
}

TEST(ProgramReader, SpacesInsideWordsAreDropped) {
  const auto segs = segments("G 0 1 X 1 0.5 F 6 0 0\n\tg1\ty\t2 0\n");
  ASSERT_EQ(segs.size(), 2u);
  EXPECT_EQ(segs[0].kind, MotionKind::Linear);
  EXPECT_DOUBLE_EQ(segs[0].end[0], 10.5);
  EXPECT_DOUBLE_EQ(segs[1].end[1], 20.0);
}

TEST(ProgramReader, LettersAreCaseInsensitive) {
  const auto segs = segments("g1 x20 y30 f600 m3 s10\n");
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_POSE_NEAR(segs[0].end, pose(20, 30, 10), 1e-12);
  EXPECT_EQ(segs[0].laser, LaserMode::Constant);
}

TEST(ProgramReader, NumberForms) {
  const auto segs = segments("G1 X1. Y.5 Z+1 F600\nG91 X-0.5 Y-.25\nG90 G01 X010\nG0 X11\nG1.0 X12\n");
  ASSERT_EQ(segs.size(), 5u);
  EXPECT_POSE_NEAR(segs[0].end, pose(1, 0.5, 1), 1e-15);
  EXPECT_POSE_NEAR(segs[1].end, pose(0.5, 0.25, 1), 1e-15);
  EXPECT_DOUBLE_EQ(segs[2].end[0], 10.0);
  EXPECT_EQ(segs[2].kind, MotionKind::Linear);
  EXPECT_EQ(segs[3].kind, MotionKind::Rapid);
  EXPECT_EQ(segs[4].kind, MotionKind::Linear);  // G1.0 is G1
}

TEST(ProgramReader, DecimalNumbersRoundLikeStrtod) {
  const auto segs = segments("G0 X0.1 Y123.456789012345678 Z0.30000000000000004\n");
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_EQ(segs[0].end[0], 0.1);
  EXPECT_EQ(segs[0].end[1], 123.456789012345678);
  EXPECT_EQ(segs[0].end[2], 0.30000000000000004);
}

TEST(ProgramReader, LineNumbersAreAccepted) {
  ReaderOptions run_deleted = start_at();
  run_deleted.block_delete = false;
  const auto segs = segments("N10 G1 X20 F600\nn20 x30\n/N30 X40\n", run_deleted);
  ASSERT_EQ(segs.size(), 3u);
  EXPECT_EQ(segs[1].line, 2u);  // the file line, not the N number
}

TEST(ProgramReader, CrLfLinesAndByteOrderMark) {
  const auto segs = segments("\xEF\xBB\xBFG1 X20 F600\r\nX30\r\n");
  ASSERT_EQ(segs.size(), 2u);
  EXPECT_DOUBLE_EQ(segs[1].end[0], 30.0);
}

TEST(ProgramReader, LastLineWithoutNewlineIsRead) {
  const auto segs = segments("G0 X20\nG0 X30");
  ASSERT_EQ(segs.size(), 2u);
}

TEST(ProgramReader, EndAndErrorAreSticky) {
  auto reader = ProgramReader::from_string("G0 X20\n", "a.ngc", test::test_machine(), start_at());
  Segment s;
  EXPECT_EQ(reader->next(s), ProgramReader::Next::Segment);
  EXPECT_EQ(reader->next(s), ProgramReader::Next::End);
  EXPECT_EQ(reader->next(s), ProgramReader::Next::End);
  EXPECT_EQ(reader->lines_read(), 1u);

  reader = ProgramReader::from_string("G0 X20\nT1\nG0 X30\n", "b.ngc", test::test_machine(), start_at());
  EXPECT_EQ(reader->next(s), ProgramReader::Next::Segment);
  EXPECT_EQ(reader->next(s), ProgramReader::Next::Error);
  EXPECT_EQ(reader->next(s), ProgramReader::Next::Error);
  EXPECT_EQ(reader->error().line, 2u);
  EXPECT_EQ(reader->error().file, "b.ngc");
}

TEST(ProgramReader, ErrorLineProducesNoSegment) {
  // The dwell of a block that fails later (travel) is not handed out.
  const auto r = run("G1 F600\nG4 P1 X2000\n");
  EXPECT_EQ(r.last, ProgramReader::Next::Error);
  EXPECT_TRUE(r.segments.empty());
}

TEST(ProgramReader, ReadsLinesUpToTheLineBoundAcrossReadChunks) {
  // Lines as long as allowed (gcode::kMaxLineBytes), placed so that some
  // cross the boundary of the file's read chunks; longer ones are an error
  // (program_reader_bounds_test).
  std::string prog = "G1 X20 F600 (";
  for (int i = 0; i < 20; ++i) prog.append(60000, 'x') += ")\n(";
  prog += ")\nX30\n";
  const std::string path = ::testing::TempDir() + "long_line.ngc";
  {
    std::FILE* f = std::fopen(path.c_str(), "wb");
    ASSERT_NE(f, nullptr);
    std::fwrite(prog.data(), 1, prog.size(), f);
    std::fclose(f);
  }
  auto opened = ProgramReader::open(path, test::test_machine(), start_at());
  ASSERT_TRUE(opened.ok());
  Segment s;
  int n = 0;
  while ((*opened)->next(s) == ProgramReader::Next::Segment) ++n;
  EXPECT_EQ(n, 2);
  EXPECT_DOUBLE_EQ(s.end[0], 30.0);
  std::remove(path.c_str());
}

// M70 saves the modal state, M72 restores it, M71 forgets it, M73 saves it
// until the subroutine returns (LinuxCNC).
TEST(ProgramReader, M70SavesTheModalStateAndM72RestoresIt) {
  const auto segs =
      segments("F600 S50 M3 G90\nM70\nF60 S10 G91 G20 M5\nG1 X1\nM72\nG1 X20 Y20\nM72\nG1 Y30\n");
  ASSERT_EQ(segs.size(), 3u);
  EXPECT_POSE_NEAR(segs[0].end, pose(10 + 25.4, 10, 10), 1e-9);  // G91 G20 X1
  EXPECT_DOUBLE_EQ(segs[0].feed_mm_s, 60.0 * 25.4 / 60.0);
  EXPECT_EQ(segs[0].laser, LaserMode::Off);
  EXPECT_POSE_NEAR(segs[1].end, pose(20, 20, 10), 1e-12);  // G90 G21 again
  EXPECT_DOUBLE_EQ(segs[1].feed_mm_s, 10.0);
  EXPECT_EQ(segs[1].laser, LaserMode::Constant);
  EXPECT_DOUBLE_EQ(segs[1].power_pct, 50.0);
  EXPECT_POSE_NEAR(segs[2].end, pose(20, 30, 10), 1e-12);  // M72 again: still saved
}

TEST(ProgramReader, M73RestoresTheCallersStateWhenTheSubroutineReturns) {
  const std::string sub =
      "o<s> sub\nM73\nG20 G91 F5\no<s> if [#1 GT 0]\no<s> return\no<s> endif\no<s> endsub\n";
  for (const char* call : {"o<s> call [0]\n", "o<s> call [1]\n"}) {
    const auto segs = segments(sub + "G21 G90 F600\n" + call + "G1 X20 Y20\n");
    ASSERT_EQ(segs.size(), 1u) << call;
    EXPECT_POSE_NEAR(segs[0].end, pose(20, 20, 10), 1e-12) << call;
    EXPECT_DOUBLE_EQ(segs[0].feed_mm_s, 10.0) << call;
  }
  // M70 in a subroutine: nothing comes back by itself
  const auto segs = segments("o<s> sub\nM70\nG91\no<s> endsub\nG90 F600\no<s> call\nG1 X5\n");
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_DOUBLE_EQ(segs[0].end[0], 15.0);
}

TEST(ProgramReader, M72WithNothingSavedAtItsLevelIsAnError) {
  Diagnostic d = expect_error("G1 X20 F600\nM72\n", ErrorCode::GcodeFlow, 2, 1);
  EXPECT_MENTIONS(d, "no modal state saved at this call level");
  expect_error("M70\nM71\nM72\n", ErrorCode::GcodeFlow, 3, 1);
  // the program's save is not the subroutine's
  expect_error("M70\no<s> sub\nM72\no<s> endsub\no<s> call\n", ErrorCode::GcodeFlow, 3, 1);
  // one modal group with M3 M4 M5
  expect_error("M3 M70\n", ErrorCode::GcodeModalConflict, 1, 4);
  // a restore under cutter compensation would move the path under it
  expect_error("M70\nG0 X100 Y95\nG41.1 D2\nG1 X100 Y100 F600\nM72\n", ErrorCode::GcodeModalConflict, 5, 1);
}

// M62/M63 switch a digital output with the next move, M64/M65 from where
// they stand (a dwell after them too); M67/M68 the same for analog outputs.
TEST(ProgramReader, OutputsSwitchWithTheNextMoveOrWhereTheyStand) {
  const auto segs = segments(
      "G1 X20 F600\nM62 P1\nG4 P0.5\nG1 X30\nM64 P3\nG4 P0.5\nM63 P1\nM65 P3\n"
      "M67 E2 Q4.5\nG1 X40\nM68 E0 Q-1\nG4 P1\n");
  ASSERT_EQ(segs.size(), 6u);
  EXPECT_EQ(segs[0].digital_out, 0u);
  EXPECT_EQ(segs[1].kind, MotionKind::Dwell);
  EXPECT_EQ(segs[1].digital_out, 0u);  // M62 waits for the move
  EXPECT_EQ(segs[2].digital_out, 0b10u);
  EXPECT_EQ(segs[3].digital_out, 0b1010u);  // M64 at once: the dwell has it
  EXPECT_EQ(segs[4].digital_out, 0u);       // M65 now, M63 with this move
  EXPECT_EQ(segs[4].analog_out[2], 4.5f);
  EXPECT_EQ(segs[5].analog_out[0], -1.0f);
  EXPECT_EQ(segs[5].analog_out[2], 4.5f);
  // M64 supersedes an M63 of the same output still waiting for a move
  const auto now = segments("M62 P0\nM65 P0\nG1 X20 F600\n");
  ASSERT_EQ(now.size(), 1u);
  EXPECT_EQ(now[0].digital_out, 0u);
}

TEST(ProgramReader, OutputWordsAreCheckedAtTheirColumn) {
  Diagnostic d = expect_error("M62\n", ErrorCode::GcodeMissingWord, 1, 1);
  EXPECT_MENTIONS(d, "M62' P<output 0 … 7>");
  d = expect_error("M64 P8\n", ErrorCode::GcodeBadValue, 1, 5);
  EXPECT_MENTIONS(d, "expected an output from 0 to 7");
  expect_error("M67 E4 Q1\n", ErrorCode::GcodeBadValue, 1, 5);
  expect_error("M68 E1\n", ErrorCode::GcodeMissingWord, 1, 1);
  expect_error("M62 P1 M64 P2\n", ErrorCode::GcodeModalConflict, 1, 8);
  d = expect_error("G1 X1e3 F600\n", ErrorCode::GcodeUnsupported, 1, 6);
  EXPECT_MENTIONS(d, "with no M67 or M68 to use it");
}

// M66 waits for a digital input at rest (a two-period dwell carrying the
// wait); the program, read ahead, sees #5399 as it will be if the job goes
// on; a wait it cannot honour so is refused.
TEST(ProgramReader, M66WaitsAtRestForAnInputWithATimeout) {
  const auto segs =
      segments("G1 X20 F600 M3 S50\nM66 P2 L3 Q1.5\nG1 X[29 + #5399]\nM66 P0 L2 Q2\nG1 X[40 + #5399]\n");
  ASSERT_EQ(segs.size(), 5u);
  const Segment& w = segs[1];
  EXPECT_EQ(w.kind, MotionKind::Dwell);
  EXPECT_EQ(w.wait_input, 2);
  EXPECT_EQ(w.wait_mode, 3u);
  EXPECT_FLOAT_EQ(w.wait_timeout_s, 1.5f);
  EXPECT_EQ(w.laser, LaserMode::Off);
  EXPECT_POSE_NEAR(w.end, pose(20, 10, 10), 1e-12);
  EXPECT_EQ(segs[2].wait_input, -1);
  EXPECT_DOUBLE_EQ(segs[2].end[0], 30.0);  // L3 (high): #5399 reads 1
  EXPECT_DOUBLE_EQ(segs[4].end[0], 40.0);  // L2 (a fall): 0
  Diagnostic d = expect_error("M66 P1 L0 Q1\n", ErrorCode::GcodeUnsupported, 1, 8);
  EXPECT_MENTIONS(d, "read ahead of the motion");
  expect_error("M66 P1\n", ErrorCode::GcodeUnsupported, 1, 1);  // L0 by default
  d = expect_error("M66 P1 L3\n", ErrorCode::GcodeBadValue, 1, 1);
  EXPECT_MENTIONS(d, "needs a timeout");
  expect_error("M66 P8 L3 Q1\n", ErrorCode::GcodeBadValue, 1, 5);
  expect_error("M66 E0 L3 Q1\n", ErrorCode::GcodeUnsupported, 1, 5);
  expect_error("M66 L3 Q1\n", ErrorCode::GcodeMissingWord, 1, 1);
  expect_error("G0 X100 Y95\nG41.1 D2\nG1 X100 Y100 F600\nM66 P1 L3 Q1\n", ErrorCode::GcodeModalConflict, 4,
               1);
}

// M48 … M53 (LinuxCNC's override switches): each move carries how the
// operator's override and the machine's feed inputs act on it; M72
// restores them; the #<_…> parameters read them. (Each job starts with
// the overrides on: M2's reset of them in LinuxCNC has nothing to act on.)
TEST(ProgramReader, OverrideSwitchesTravelWithTheMovesAfterThem) {
  const auto segs = segments(
      "G1 X20 F600\nM50 P0\nG1 X30\nM52\nG1 X40\nM53 P0\nG1 X50\nM48\nG1 X60\n"
      "M52 P0\nM53 P1\nG1 X70\nM49\nG1 X80\nM70\nM50 P1\nG1 X90\nM72\nG1 X100\n"
      "G1 Y[20 + #<_feed_override> + 2 * #<_speed_override> + 4 * #<_adaptive_feed> + "
      "8 * #<_feed_hold>]\nM2\n");
  ASSERT_EQ(segs.size(), 10u);
  const std::uint8_t expected[] = {0,
                                   kFeedOverrideOff,
                                   kFeedOverrideOff | kAdaptiveFeed,
                                   kFeedOverrideOff | kAdaptiveFeed | kFeedHoldInputOff,
                                   kAdaptiveFeed | kFeedHoldInputOff,
                                   0,
                                   kFeedOverrideOff,
                                   0,
                                   kFeedOverrideOff,
                                   kFeedOverrideOff};
  for (std::size_t i = 0; i < segs.size(); ++i) EXPECT_EQ(segs[i].feed_control, expected[i]) << i;
  // after M49 and M72: feed override off (0), speed override off (0), no
  // adaptive feed (0), the feed-hold input on (8)
  EXPECT_DOUBLE_EQ(segs[9].end[1], 28.0);
}

TEST(ProgramReader, OverrideSwitchWordsAreCheckedAtTheirColumn) {
  expect_error("M48 P1\n", ErrorCode::GcodeUnsupported, 1, 5);  // M48/M49 take no P
  expect_error("M50 P0.5\n", ErrorCode::GcodeBadValue, 1, 5);
  expect_error("M50 P-1\n", ErrorCode::GcodeBadValue, 1, 5);
  Diagnostic d = expect_error("M50 P0 M52\n", ErrorCode::GcodeModalConflict, 1, 8);
  EXPECT_MENTIONS(d, "M modal group 9");
  d = expect_error("G0 X100 Y95\nG41.1 D2\nG1 X100 Y100 F600\nM50 P0\n", ErrorCode::GcodeModalConflict, 4, 1);
  EXPECT_MENTIONS(d, "cutter compensation");
}

}  // namespace
}  // namespace lcnc

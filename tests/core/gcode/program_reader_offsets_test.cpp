// Coordinate systems, G92/G52, G53, G28/G30, tools and the parameter file,
// as LinuxCNC runs them: machine = program + work offset + G92 + tool offset.
// (tests/data/linuxcnc_compare/offsets_and_tools.ngc runs the same codes
// through LinuxCNC's own interpreter in the e2e comparison.)
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/gcode/gcode_test_util.h"
#include "gcode/parameter_file.h"
#include "machine/machine_config.h"

namespace lcnc {
namespace {

namespace fs = std::filesystem;
using test::expect_error;
using test::pose;
using test::segments;

MachineConfig tool_machine_program_reader_offsets() {
  MachineConfig m = test::test_machine();
  ToolConfig t1;
  t1.number = 1;
  t1.offset = pose(0, 0, 2.5);
  t1.diameter_mm = 0.2;
  t1.description = "nozzle 1.5 mm";
  ToolConfig t4;
  t4.number = 4;
  t4.offset = pose(0, 0, -1.0);
  m.tools = {t1, t4};
  return m;
}

fs::path temp_dir() {
  const fs::path d = fs::temp_directory_path() /
                     ("lcnc_offsets_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
                      "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

TEST(ProgramOffsets, G92MakesTheCurrentPositionReadAsItsWordsAndG921G922G923ClearAndRestore) {
  // start at (10, 10, 10): G92 X1 makes X read 1 there, so X0 is machine 9
  const auto segs = segments("G92 X1\nG0 X0\nG92.2\nG0 X0\nG92.3\nG0 X2\nG92.1\nG92.3\nG0 X5\n");
  ASSERT_EQ(segs.size(), 4u);
  EXPECT_DOUBLE_EQ(segs[0].end[0], 9.0);
  EXPECT_DOUBLE_EQ(segs[1].end[0], 0.0);   // G92.2: no offset
  EXPECT_DOUBLE_EQ(segs[2].end[0], 11.0);  // G92.3: back (9 + 2)
  EXPECT_DOUBLE_EQ(segs[3].end[0], 5.0);   // G92.1 zeroed the parameters too
  EXPECT_EQ(segs[0].kind, MotionKind::Rapid);
}

TEST(ProgramOffsets, G52SetsTheAxisOffsetToItsWords) {
  const auto segs = segments("G92 X1\nG52 X2\nG0 X0\nG52 X0\nG0 X0\n");
  ASSERT_EQ(segs.size(), 2u);
  EXPECT_DOUBLE_EQ(segs[0].end[0], 2.0);
  EXPECT_DOUBLE_EQ(segs[1].end[0], 0.0);
}

TEST(ProgramOffsets, G10L2SetsASystemAndTheSystemInEffectAtOnce) {
  // G55 is X+500 in the test machine; G10 L2 P2 moves it, P0 is G54 here
  const auto segs =
      segments("G10 L2 P2 X100 Y20\nG55 G0 X0 Y0\nG54\nG10 L2 P0 X3\nG0 X0\nG10 L2 P7 X50\nG59.1 G0 X1\n");
  ASSERT_EQ(segs.size(), 3u);
  EXPECT_POSE_NEAR(segs[0].end, pose(100, 20, 10), 1e-12);
  EXPECT_DOUBLE_EQ(segs[1].end[0], 3.0);
  EXPECT_DOUBLE_EQ(segs[2].end[0], 51.0);
}

TEST(ProgramOffsets, G10L20MakesTheCurrentPositionReadAsItsWordsWithG92InEffect) {
  // at X10 with G92 X1 (offset 9): L20 X5 puts G54 at 10 − 9 − 5 = −4
  const auto segs = segments("G92 X1\nG10 L20 P1 X5\nG0 X0\nG92.1\nG0 X20\n");
  ASSERT_EQ(segs.size(), 2u);
  EXPECT_DOUBLE_EQ(segs[0].end[0], 5.0);
  EXPECT_DOUBLE_EQ(segs[1].end[0], 16.0);
}

TEST(ProgramOffsets, G53MovesInMachineCoordinatesForItsBlockOnly) {
  const auto segs = segments("G55\nG53 G0 X5\nG0 X5\nG1 F600\nG53 X7\n");
  ASSERT_EQ(segs.size(), 3u);
  EXPECT_DOUBLE_EQ(segs[0].end[0], 5.0);
  EXPECT_DOUBLE_EQ(segs[1].end[0], 505.0);
  EXPECT_DOUBLE_EQ(segs[2].end[0], 7.0);
  EXPECT_EQ(segs[2].kind, MotionKind::Linear);
  Diagnostic d = expect_error("G91\nG53 G0 X5\n", ErrorCode::GcodeSyntax, 2, 1);
  EXPECT_MENTIONS(d, "G53 in G90");
  d = expect_error("G53 G2 X20 I5 F100\n", ErrorCode::GcodeSyntax, 1, 1);
  EXPECT_MENTIONS(d, "G53 with G0 or G1");
}

TEST(ProgramOffsets, G28GoesThroughItsWordsThenOnlyThoseAxesHomeG28WithoutWordsAll) {
  // G28.1 stores (10, 10, 10); from (50, 50, 10) G28 Z20 goes up to Z20, then
  // Z to 10; G28 alone takes every axis there
  const auto segs = segments("G28.1\nG0 X50 Y50\nG28 Z20\nG28\nG0 X1 Y2 Z3\nG30.1\nG0 X0\nG30\n");
  ASSERT_EQ(segs.size(), 7u);
  EXPECT_POSE_NEAR(segs[1].end, pose(50, 50, 20), 1e-12);
  EXPECT_POSE_NEAR(segs[2].end, pose(50, 50, 10), 1e-12);
  EXPECT_POSE_NEAR(segs[3].end, pose(10, 10, 10), 1e-12);
  EXPECT_EQ(segs[1].kind, MotionKind::Rapid);
  EXPECT_POSE_NEAR(segs[6].end, pose(1, 2, 3), 1e-12);
}

TEST(ProgramOffsets, TwoCodesUsingTheAxisWordsAreAConflict) {
  const Diagnostic d = expect_error("G1 G92 X1 F100\n", ErrorCode::GcodeModalConflict, 1, 1);
  EXPECT_MENTIONS(d, "both using its axis words");
  expect_error("G92\n", ErrorCode::GcodeMissingWord, 1, 1);
  expect_error("G10 L2 X1\n", ErrorCode::GcodeMissingWord, 1, 1);
  expect_error("G10 L2 P10 X1\n", ErrorCode::GcodeBadValue, 1, 8);
  expect_error("G10 L3 P1 X1\n", ErrorCode::GcodeUnsupported, 1, 5);
  const Diagnostic r = expect_error("G10 L2 P1 R30\n", ErrorCode::GcodeUnsupported, 1, 11);
  EXPECT_MENTIONS(r, "rotated coordinate system");
}

TEST(ProgramTools, G43AppliesTheToolsZOffsetAndG49RemovesIt) {
  const MachineConfig m = tool_machine_program_reader_offsets();
  const auto segs =
      segments("T1 M6\nG43\nG0 Z0\nT4 M6 G43\nG0 Z5\nG49\nG0 Z5\nG43 H1\nG0 Z0\n", test::start_at(), m);
  ASSERT_EQ(segs.size(), 4u);
  EXPECT_DOUBLE_EQ(segs[0].end[2], 2.5);
  EXPECT_DOUBLE_EQ(segs[1].end[2], 4.0);
  EXPECT_DOUBLE_EQ(segs[2].end[2], 5.0);
  EXPECT_DOUBLE_EQ(segs[3].end[2], 2.5);
}

TEST(ProgramTools, AToolNotInTheTableIsAnErrorAtItsWord) {
  const MachineConfig m = tool_machine_program_reader_offsets();
  Diagnostic d = expect_error("G0 X1\nT7 M6\n", ErrorCode::GcodeNoSuchTool, 2, 1, test::start_at(), m);
  EXPECT_MENTIONS(d, "tool 7 is not in the tool table");
  EXPECT_MENTIONS(d, "one of 1 4");
  d = expect_error("G43 H9\n", ErrorCode::GcodeNoSuchTool, 1, 5, test::start_at(), m);
  expect_error("M61\n", ErrorCode::GcodeMissingWord, 1, 1, test::start_at(), m);
  expect_error("T1.5\n", ErrorCode::GcodeBadValue, 1, 1, test::start_at(), m);
  // T0 is no tool, always there
  EXPECT_EQ(segments("T0 M6\nG43\nG0 Z1\n", test::start_at(), m).at(0).end[2], 1.0);
}

TEST(ProgramTools, M61G431G432AndG10L1L10SetTheOffsets) {
  const MachineConfig m = tool_machine_program_reader_offsets();
  const auto segs = segments(
      "M61 Q4\nG43\nG0 Z5\n"                       // −1
      "G43.1 Z3\nG0 Z0\n"                          // 3
      "G43.2 H1\nG0 Z0\n"                          // 3 + 2.5
      "G10 L1 P1 Z7 R0.1\nG43 H1\nG0 Z0\n"         // 7
      "G0 Z20\nG10 L10 P4 Z10\nG43 H4\nG0 Z10\n",  // L10 at machine Z27: Z reads 10 with offset 17
      test::start_at(), m);
  ASSERT_EQ(segs.size(), 5u);
  EXPECT_DOUBLE_EQ(segs[0].end[2], 4.0);
  EXPECT_DOUBLE_EQ(segs[1].end[2], 3.0);
  EXPECT_DOUBLE_EQ(segs[2].end[2], 5.5);
  EXPECT_DOUBLE_EQ(segs[3].end[2], 7.0);
  EXPECT_DOUBLE_EQ(segs[4].end[2], 27.0);  // G0 Z20 (offset 7); then Z10 with 17 is where it stands
}

TEST(ProgramParametersOffsets, ProgramsReadPositionOffsetsAndToolsAsLinuxCncNumbersThem) {
  const MachineConfig m = tool_machine_program_reader_offsets();
  // #5420 … the position in program coordinates, #5221 G54's X, #5400 the
  // tool in the spindle, #<_x> the same as #5420, in the program's units
  const auto segs = segments(
      "G10 L2 P1 X5\nG0 X15\n#1 = #5420\n#2 = #5221\nT1 M6\n#3 = #5400\n#4 = #<_current_tool>\n"
      "G20\n#5 = #<_x>\nG21\n#6 = #<_coord_system>\n"
      "G1 X[#1 + #2 + #3 + #4] Y[#5 * 25.4] Z[#6 - 530] F600\n",
      test::start_at(), m);
  ASSERT_EQ(segs.size(), 2u);
  EXPECT_DOUBLE_EQ(segs[1].end[0], 5.0 + 15.0 + 5.0 + 1.0 + 1.0);
  EXPECT_NEAR(segs[1].end[1], 15.0, 1e-9);  // X read 15 mm as 0.5906 in
  EXPECT_DOUBLE_EQ(segs[1].end[2], 10.0);   // G54 is 540
}

TEST(ParameterFile, AJobKeepsItsOffsetsAndToolsForTheNextAndACheckWritesNothing) {
  const fs::path dir = temp_dir();
  MachineConfig m = tool_machine_program_reader_offsets();
  m.parameter_file = (dir / "lasercnc.var").string();
  // at (10, 10, 10) in G55 = (100, 20): G92 X1 is an axis offset of −91
  const std::string setter = "G10 L2 P2 X100 Y20\nG55\nG92 X1\nG28.1\nG10 L1 P4 Z3 R0.25\nM2\n";
  // a check (keep_parameters off) writes nothing
  segments(setter, test::start_at(), m);
  EXPECT_FALSE(fs::exists(m.parameter_file));
  ReaderOptions job = test::start_at();
  job.keep_parameters = true;
  segments(setter, job, m);
  ASSERT_TRUE(fs::exists(m.parameter_file));
  for (const auto& e : fs::directory_iterator(dir))  // no temporary file left
    EXPECT_EQ(e.path().filename().string().rfind(".lasercnc.var.", 0), std::string::npos) << e.path();
  // the next job: G55 as set (M2 returned to G54), G92 still on, G28 stored, tool 4 changed
  const auto segs = segments("G55 G0 X0 Y0\nG92.1\nG28\nG43 H4\nG0 Z0\n", test::start_at(50, 50, 50), m);
  ASSERT_EQ(segs.size(), 3u);
  EXPECT_POSE_NEAR(segs[0].end, pose(100 - 91, 20, 50), 1e-12);
  EXPECT_POSE_NEAR(segs[1].end, pose(10, 10, 10), 1e-12);
  EXPECT_DOUBLE_EQ(segs[2].end[2], 3.0);
  Result<gcode::ParameterFileData> kept = gcode::read_parameter_file(m.parameter_file);
  ASSERT_TRUE(kept) << kept.error().to_string();
  ASSERT_EQ(kept->tools.size(), 1u);
  EXPECT_EQ(kept->tools[0].number, 4);
  EXPECT_DOUBLE_EQ(kept->tools[0].diameter_mm, 0.5);
  fs::remove_all(dir);
}

TEST(ParameterFile, AMalformedFileIsAnErrorAtItsLineAndColumnBeforeAnythingRuns) {
  const fs::path dir = temp_dir();
  MachineConfig m = tool_machine_program_reader_offsets();
  m.parameter_file = (dir / "bad.var").string();
  std::ofstream(m.parameter_file) << "5221\t1.5\n5222 abc\n";
  test::Run r = test::run("G0 X1\n", test::start_at(), m);
  ASSERT_EQ(r.last, ProgramReader::Next::Error);
  EXPECT_EQ(r.error.code, ErrorCode::ParameterFileBad);
  EXPECT_EQ(r.error.file, m.parameter_file);
  EXPECT_EQ(r.error.line, 2u);
  EXPECT_EQ(r.error.col, 6u);
  EXPECT_TRUE(r.segments.empty());
  std::ofstream(m.parameter_file) << "5221 1.5\n42 7\n";
  r = test::run("G0 X1\n", test::start_at(), m);
  EXPECT_EQ(r.error.code, ErrorCode::ParameterFileBad);
  EXPECT_MENTIONS(r.error, "from 5161 to 5390");
  std::ofstream(m.parameter_file) << "T4 Z1 Q7\n";
  r = test::run("G0 X1\n", test::start_at(), m);
  EXPECT_EQ(r.error.code, ErrorCode::ParameterFileBad);
  EXPECT_EQ(r.error.col, 7u);
  // a good one: G54 at X1.5
  std::ofstream(m.parameter_file) << "5221\t1.5\n; a comment\n";
  const auto segs = segments("G0 X0\n", test::start_at(), m);
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_DOUBLE_EQ(segs[0].end[0], 1.5);
  fs::remove_all(dir);
}

// Offsets a job sets but cannot keep are not reported as kept: the reading
// that should store them fails at its end, naming the file (the daemon then
// refuses the MDI G10, a job fails), and the file stays as it was.
TEST(ParameterFile, OffsetsThatCannotBeKeptFailTheReadingThatSetThem) {
  const fs::path dir = temp_dir();
  MachineConfig m = tool_machine_program_reader_offsets();
  m.parameter_file = (dir / "gone" / "lasercnc.var").string();  // its folder does not exist
  ReaderOptions job = test::start_at();
  job.keep_parameters = true;
  const test::Run r = test::run("G10 L2 P1 X20\nG0 X1\nM2\n", job, m);
  ASSERT_EQ(r.last, ProgramReader::Next::Error);
  EXPECT_EQ(r.error.code, ErrorCode::ParameterFileBad);
  EXPECT_EQ(r.error.file, m.parameter_file);
  EXPECT_MENTIONS(r.error, "not kept");
  EXPECT_EQ(r.segments.size(), 1u);  // its moves were read; its end is the error
  // a reading that keeps nothing (a check) is not concerned
  EXPECT_EQ(test::run("G10 L2 P1 X20\nG0 X1\nM2\n", test::start_at(), m).last, ProgramReader::Next::End);
  fs::remove_all(dir);
}

// A value that is there but does not parse is named as such (not "no
// value"), and bytes that cannot be shown are escaped: a NUL no longer cuts
// the message off.
TEST(ParameterFile, AValueThatDoesNotParseIsNamedAndItsBytesEscaped) {
  const fs::path dir = temp_dir();
  MachineConfig m = tool_machine_program_reader_offsets();
  m.parameter_file = (dir / "bad.var").string();
  const auto error_of = [&](const std::string& text) {
    std::ofstream(m.parameter_file, std::ios::binary) << text;
    const test::Run r = test::run("G0 X1\n", test::start_at(), m);
    EXPECT_EQ(r.last, ProgramReader::Next::Error) << text;
    EXPECT_EQ(r.error.code, ErrorCode::ParameterFileBad);
    EXPECT_TRUE(r.segments.empty());
    return r.error;
  };
  Diagnostic d = error_of("5221 1e400\n");
  EXPECT_MENTIONS(d, "'1e400' as the value of parameter 5221: not a finite number");
  EXPECT_EQ(d.col, 6u);
  d = error_of("5221 abc\n");
  EXPECT_MENTIONS(d, "'abc' as the value of parameter 5221: not a number");
  d = error_of("5221\n");
  EXPECT_MENTIONS(d, "parameter 5221 with no value");
  d = error_of(std::string("5221 1 x\0y tail\n", 16));
  EXPECT_MENTIONS(d, "'x\\x00y tail' after the value");
  d = error_of(std::string("\x1b[2J5221 1\n"));
  EXPECT_MENTIONS(d, "'\\x1B[2J5221 1'");
  fs::remove_all(dir);
}

TEST(MachineConfigTools, ToolsAndTheNineWorkOffsetsAreReadFromToml) {
  Result<MachineConfig> m = parse_machine_config(R"(
[machine]
parameter_file = "state/lasercnc.var"
[axes.X]
min = 0
max = 100
max_velocity = 10
max_acceleration = 100
[tools.3]
z_offset = 1.25
diameter = 0.15
description = "nozzle 2.0, lens 150"
[tools.1]
z_offset = -0.5
[work_offsets]
"G59.3" = [1, 2, 3, 0, 0, 0]
)",
                                                 "/etc/lasercnc/m.toml");
  ASSERT_TRUE(m) << m.error().to_string();
  ASSERT_EQ(m->tools.size(), 2u);
  EXPECT_EQ(m->tools[0].number, 1);
  EXPECT_EQ(m->tools[1].number, 3);
  EXPECT_DOUBLE_EQ(m->tools[1].offset[2], 1.25);
  EXPECT_DOUBLE_EQ(m->tools[1].diameter_mm, 0.15);
  EXPECT_EQ(m->tools[1].description, "nozzle 2.0, lens 150");
  EXPECT_DOUBLE_EQ(m->work_offsets[8][1], 2.0);
  EXPECT_EQ(m->parameter_file, "/etc/lasercnc/state/lasercnc.var");
  Result<MachineConfig> bad = parse_machine_config("[tools.0]\nz_offset = 1\n", "m.toml");
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.error().code, ErrorCode::ConfigBadValue);
  EXPECT_EQ(bad.error().line, 1u);
  bad = parse_machine_config("[tools.2]\nlength = 1\n", "m.toml");
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.error().code, ErrorCode::ConfigUnknownKey);
  EXPECT_EQ(bad.error().line, 2u);
}

}  // namespace
}  // namespace lcnc

// Parameters and expressions in programs, as LinuxCNC reads them: a line's
// settings take effect after all of its values are read.
#include <gtest/gtest.h>

#include "core/gcode/gcode_test_util.h"

namespace lcnc {
namespace {

using test::expect_error;
using test::segments;

TEST(ProgramParameters, NumberedAndNamedParametersFeedWords) {
  const auto segs = segments(
      "#1 = 20\n#<feed> = 600\n#<_half> = [#1 / 2]\nG1 X#1 Y#<_half> F#<feed>\nG1 X[#1 + 10] Y[SIN[30] * "
      "40]\n");
  ASSERT_EQ(segs.size(), 2u);
  EXPECT_DOUBLE_EQ(segs[0].end[0], 20.0);
  EXPECT_DOUBLE_EQ(segs[0].end[1], 10.0);
  EXPECT_DOUBLE_EQ(segs[0].feed_mm_s, 10.0);
  EXPECT_DOUBLE_EQ(segs[1].end[0], 30.0);
  EXPECT_NEAR(segs[1].end[1], 20.0, 1e-12);
}

TEST(ProgramParameters, ASettingTakesEffectAfterItsLine) {
  // #2 reads #1 as it was before the line; X reads it too
  const auto segs = segments("#1 = 15\n#1 = 25 #2 = #1 G1 X#1 F600\nG1 Y#2\nG1 X#1\n");
  ASSERT_EQ(segs.size(), 3u);
  EXPECT_DOUBLE_EQ(segs[0].end[0], 15.0);
  EXPECT_DOUBLE_EQ(segs[1].end[1], 15.0);
  EXPECT_DOUBLE_EQ(segs[2].end[0], 25.0);
}

TEST(ProgramParameters, UnsetNumberedReadsZeroUnsetNamedIsAnError) {
  const auto segs = segments("G1 X[20 + #100] F600\n");
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_DOUBLE_EQ(segs[0].end[0], 20.0);
  const Diagnostic d = expect_error("G1 X#<depth> F600\n", ErrorCode::GcodeSyntax, 1, 5);
  EXPECT_MENTIONS(d, "#<depth>");
  EXPECT_MENTIONS(d, "not defined");
}

TEST(ProgramParameters, ErrorsPointAtTheColumn) {
  Diagnostic d = expect_error("G1 X[10 / 0] F600\n", ErrorCode::GcodeBadValue, 1, 9);
  EXPECT_MENTIONS(d, "division by zero");
  d = expect_error("#1 10\n", ErrorCode::GcodeSyntax, 1, 1);
  EXPECT_MENTIONS(d, "'='");
  d = expect_error("#6000 = 1\n", ErrorCode::GcodeBadValue, 1, 2);
  EXPECT_MENTIONS(d, "from 1 to 5602");
  d = expect_error("G1 X[1 + 2 F600\n", ErrorCode::GcodeSyntax, 1, 12);
  EXPECT_MENTIONS(d, "expected an operator");
  d = expect_error("G1 X[1 + 2\n", ErrorCode::GcodeSyntax, 1, 5);
  EXPECT_MENTIONS(d, "not closed");
}

// LinuxCNC's read-only parameters stay read-only: set, #<_x> read back
// what was set while the machine stood elsewhere (a program that moved "to
// X510" with the machine at X100). An error at the setting, naming it.
TEST(ProgramParameters, ReadOnlyParametersAreRefusedWhereTheyAreSet) {
  for (const char* p : {"#<_x>", "#<_Y>", "#<_abs_z>", "#<_current_tool>", "#<_feed>", "#<_coord_system>",
                        "#5420", "#5422", "#5400", "#5410", "#5399"}) {
    SCOPED_TRACE(p);
    const Diagnostic d =
        expect_error(std::string("G1 X10 F600\nG0 ") + p + " = 500\n", ErrorCode::GcodeBadValue, 2, 4);
    EXPECT_MENTIONS(d, "read-only");
  }
  // the reading goes on to the one that is not
  const auto segs = segments("#<_mine> = 5\n#5161 = 2\nG1 X[#<_mine> + #5161] F600\n");
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_DOUBLE_EQ(segs[0].end[0], 7.0);
}

TEST(ProgramParameters, BlockDeletedSettingsAreSkipped) {
  const auto segs = segments("#1 = 20\n/#1 = 40\nG1 X#1 F600\n");
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_DOUBLE_EQ(segs[0].end[0], 20.0);
}

}  // namespace
}  // namespace lcnc

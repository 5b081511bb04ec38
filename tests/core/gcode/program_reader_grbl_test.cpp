// The grbl dialect ([machine] dialect = "grbl"): the files hobby laser
// design tools write (LightBurn's GRBL profile) run as they are.
#include <gtest/gtest.h>

#include "core/gcode/gcode_test_util.h"
#include "machine/machine_config.h"

namespace lcnc {
namespace {

using test::expect_error;
using test::start_at;

// LightBurn 1.4's GRBL output for a 50 × 30 mm rectangle at 60 % power,
// with the homing and unlock lines some users add in front.
constexpr const char* kLightBurn =
    "$H\n"
    "$X\n"
    "; LightBurn 1.4.03\n"
    "; GRBL device profile, absolute coords\n"
    "; Bounds: X10 Y10 to X60 Y40\n"
    "G00 G17 G40 G21 G54\n"
    "G90\n"
    "M4\n"
    "; Cut @ 1200 mm/min, 60% power\n"
    "M8\n"
    "G0X10Y10\n"
    "; Layer C00\n"
    "G1Y40S600F1200\n"
    "G1X60\n"
    "G1Y10\n"
    "G1X10\n"
    "M9\n"
    "G1S0\n"
    "M5\n"
    "G90\n"
    "; return to user-defined finish pos\n"
    "G0 X0 Y0\n"
    "M2\n";

MachineConfig grbl_machine() {
  Result<MachineConfig> m = parse_machine_config(R"(
[machine]
dialect = "grbl"
[axes.X]
min = 0
max = 400
max_velocity = 100
max_acceleration = 1000
[axes.Y]
min = 0
max = 400
max_velocity = 100
max_acceleration = 1000
)",
                                                 "grbl.toml");
  EXPECT_TRUE(m) << m.error().to_string();
  return *m;
}

TEST(GrblDialect, ALightBurnFileRunsWithSUpTo1000AndM4DynamicPower) {
  const MachineConfig m = grbl_machine();
  EXPECT_DOUBLE_EQ(m.laser.s_max, 1000.0);
  const test::Run r = test::run(kLightBurn, start_at(0, 0, 0), m);
  ASSERT_EQ(r.last, ProgramReader::Next::End) << r.error.to_string();
  ASSERT_EQ(r.segments.size(), 6u);
  const Segment& cut = r.segments[1];
  EXPECT_EQ(cut.laser, LaserMode::Dynamic);
  EXPECT_DOUBLE_EQ(cut.power_pct, 60.0);
  EXPECT_DOUBLE_EQ(cut.feed_mm_s, 20.0);
  EXPECT_TRUE(cut.flood);
  // $H and $X: passed over, each a warning at its line
  ASSERT_GE(r.warnings.size(), 2u);
  EXPECT_EQ(r.warnings[0].code, ErrorCode::GcodeLinePassedOver);
  EXPECT_EQ(r.warnings[0].line, 1u);
  EXPECT_EQ(r.warnings[1].line, 2u);
  EXPECT_MENTIONS(r.warnings[0], "'$H'");
}

TEST(GrblDialect, TheSameFileOnAnRs274ngcMachineSaysWhereItDiffers) {
  // a "$H" line is not G-code; S600 is past the default s_max of 100
  const Diagnostic h = expect_error(kLightBurn, ErrorCode::GcodeSyntax, 1, 1);
  EXPECT_MENTIONS(h, "dialect = \"grbl\"");
  MachineConfig m = grbl_machine();
  m.dialect = MachineConfig::Dialect::Rs274ngc;
  m.laser.s_max = 100.0;
  const std::string body = std::string(kLightBurn).substr(6);  // without $H, $X
  const Diagnostic d = expect_error(body, ErrorCode::GcodeBadValue, 11, 6, start_at(0, 0, 0), m);
  EXPECT_MENTIONS(d, "expected S from 0 to 100");
}

TEST(GrblDialect, TheDialectKeyIsCheckedAndSMaxStillWins) {
  Result<MachineConfig> m = parse_machine_config(
      "[machine]\ndialect = \"grbl\"\n[laser]\ns_max = 255\n[axes.X]\nmin = 0\nmax = 10\n"
      "max_velocity = 10\nmax_acceleration = 100\n",
      "m.toml");
  ASSERT_TRUE(m) << m.error().to_string();
  EXPECT_DOUBLE_EQ(m->laser.s_max, 255.0);
  m = parse_machine_config("[machine]\ndialect = \"marlin\"\n", "m.toml");
  ASSERT_FALSE(m);
  EXPECT_EQ(m.error().code, ErrorCode::ConfigBadValue);
  EXPECT_EQ(m.error().line, 2u);
  EXPECT_MENTIONS(m.error(), "\"grbl\"");
}

}  // namespace
}  // namespace lcnc

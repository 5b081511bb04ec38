#include "machine/machine_config.h"

#include <gtest/gtest.h>

#include <cstring>
#include <new>

#include <string>

namespace lcnc {
namespace {

const std::string kShare = std::string(LCNC_SOURCE_DIR) + "/share";

const char* kMinimalMachineConfig = R"(
[machine]
period_us = 75
[dda]
magnitude_bits = 4
capacity = 30
[axes.X]
min = 0
max = 100
max_velocity = 150
max_acceleration = 1000
steps_per_unit = 1000
)";

TEST(MachineConfig, DefaultMachineLoadsAsDesigned) {
  auto m = load_machine_config(kShare + "/machines/default.toml");
  ASSERT_TRUE(m) << m.error().to_string();
  EXPECT_EQ(m->period_ns, 75'000u);
  EXPECT_TRUE(m->axis(Axis::X).present);
  EXPECT_DOUBLE_EQ(m->axis(Axis::X).max, 1000.0);
  EXPECT_DOUBLE_EQ(m->axis(Axis::Y).max, 450.0);
  EXPECT_DOUBLE_EQ(m->axis(Axis::Z).max, 500.0);
  EXPECT_DOUBLE_EQ(m->axis(Axis::A).min, -95.0);
  EXPECT_TRUE(m->axis(Axis::C).wrap);
  EXPECT_FALSE(m->axis(Axis::B).present);
  EXPECT_DOUBLE_EQ(m->axis(Axis::X).steps_per_unit, 1000.0);
  EXPECT_DOUBLE_EQ(m->work_offsets[1][0], 500.0);  // G55
  EXPECT_NEAR(m->dda_clock_hz(), 4e6, 1e-3);
}

TEST(MachineConfig, SeedPresetGivesFifteenPulsesAt400kHz) {
  auto m = parse_machine_config(kMinimalMachineConfig, "seed.toml");
  ASSERT_TRUE(m) << m.error().to_string();
  EXPECT_EQ(m->dda.max_pulses(), 15u);
  EXPECT_NEAR(m->dda_clock_hz(), 400e3, 1e-6);
}

TEST(MachineConfig, MissingFileIsFileNotFound) {
  auto m = load_machine_config("/nonexistent/machine.toml");
  ASSERT_FALSE(m);
  EXPECT_EQ(m.error().code, ErrorCode::FileNotFound);
}

TEST(MachineConfig, SyntaxErrorNamesLineAndColumn) {
  auto m = parse_machine_config("[machine]\nperiod_us = = 75\n", "bad.toml");
  ASSERT_FALSE(m);
  EXPECT_EQ(m.error().code, ErrorCode::ConfigSyntax);
  EXPECT_EQ(m.error().line, 2u);
  EXPECT_GT(m.error().col, 0u);
  EXPECT_NE(m.error().to_string().find("bad.toml:2:"), std::string::npos);
}

TEST(MachineConfig, UnknownKeyIsAnErrorWithItsPlace) {
  std::string text = kMinimalMachineConfig;
  text += "max_velocty = 3\n";  // misspelt, inside [axes.X]
  auto m = parse_machine_config(text, "typo.toml");
  ASSERT_FALSE(m);
  EXPECT_EQ(m.error().code, ErrorCode::ConfigUnknownKey);
  EXPECT_NE(m.error().message.find("axes.X.max_velocty"), std::string::npos);
  EXPECT_EQ(m.error().line, 13u);
}

TEST(MachineConfig, MissingRequiredAxisKey) {
  auto m = parse_machine_config("[axes.X]\nmin = 0\nmax = 10\nmax_velocity = 10\n", "m.toml");
  ASSERT_FALSE(m);
  EXPECT_EQ(m.error().code, ErrorCode::ConfigMissingKey);
  EXPECT_NE(m.error().message.find("axes.X.max_acceleration"), std::string::npos);
}

TEST(MachineConfig, WrongTypeNamesTheKey) {
  std::string text = kMinimalMachineConfig;
  text.replace(text.find("max = 100"), 9, "max = \"100\"");
  auto m = parse_machine_config(text, "m.toml");
  ASSERT_FALSE(m);
  EXPECT_EQ(m.error().code, ErrorCode::ConfigBadValue);
  EXPECT_NE(m.error().message.find("axes.X.max"), std::string::npos);
}

TEST(MachineConfig, VelocityBeyondDdaPresetIsRejectedWithTheNumbers) {
  std::string text = kMinimalMachineConfig;
  text.replace(text.find("max_velocity = 150"), 18, "max_velocity = 250");
  auto m = parse_machine_config(text, "m.toml");
  ASSERT_FALSE(m);
  EXPECT_EQ(m.error().code, ErrorCode::ConfigBadValue);
  // 250 mm/s · 1000 steps/mm · 75 µs = 18.75 pulses > 15
  EXPECT_NE(m.error().message.find("18.75"), std::string::npos) << m.error().message;
  EXPECT_NE(m.error().message.find("15"), std::string::npos);
}

TEST(MachineConfig, RangeChecks) {
  struct Case {
    const char* from;
    const char* to;
    const char* expect;
  };
  const Case cases[] = {
      {"max = 100", "max = -5", "need min < max"},
      {"period_us = 75", "period_us = 5", "machine.period_us"},
      {"capacity = 30", "capacity = 10", "dda.capacity"},
      {"magnitude_bits = 4", "magnitude_bits = 40", "dda.magnitude_bits"},
      {"steps_per_unit = 1000", "steps_per_unit = 0", "steps_per_unit"},
      {"max_acceleration = 1000", "max_acceleration = -1", "max_acceleration"},
  };
  for (const Case& c : cases) {
    std::string text = kMinimalMachineConfig;
    const auto at = text.find(c.from);
    ASSERT_NE(at, std::string::npos) << c.from;
    text.replace(at, std::string(c.from).size(), c.to);
    auto m = parse_machine_config(text, "m.toml");
    ASSERT_FALSE(m) << c.to;
    EXPECT_EQ(m.error().code, ErrorCode::ConfigBadValue) << c.to;
    EXPECT_NE(m.error().message.find(c.expect), std::string::npos) << c.to << " -> " << m.error().message;
  }
}

TEST(MachineConfig, WrapOnlyOnRotaryAxesSpanning360) {
  std::string text = kMinimalMachineConfig;
  text += "wrap = true\n";
  auto m = parse_machine_config(text, "m.toml");
  ASSERT_FALSE(m);
  EXPECT_NE(m.error().message.find("only rotary"), std::string::npos);

  auto r = parse_machine_config(
      "[axes.C]\ntype = \"rotary\"\nmin = 0\nmax = 180\nwrap = true\nmax_velocity = 10\n"
      "max_acceleration = 100\n",
      "m.toml");
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("360"), std::string::npos);
}

TEST(MachineConfig, AxisTypeMustMatchLetter) {
  auto m = parse_machine_config(
      "[axes.A]\ntype = \"linear\"\nmin = 0\nmax = 10\nmax_velocity = 1\nmax_acceleration = 1\n", "m.toml");
  ASSERT_FALSE(m);
  EXPECT_NE(m.error().message.find("must be \"rotary\""), std::string::npos);
}

TEST(MachineConfig, WorkOffsetsNeedSixNumbers) {
  std::string text = kMinimalMachineConfig;
  text += "[work_offsets]\nG54 = [1, 2]\n";
  auto m = parse_machine_config(text, "m.toml");
  ASSERT_FALSE(m);
  EXPECT_NE(m.error().message.find("work_offsets.G54"), std::string::npos);
}

}  // namespace
}  // namespace lcnc

namespace lcnc {
namespace {

TEST(MachineConfig, MaxFeedOverrideIsReadAndBounded) {
  auto m = load_machine_config(kShare + "/machines/default.toml");
  ASSERT_TRUE(m);
  EXPECT_DOUBLE_EQ(m->max_feed_override, 1.5);
  std::string text = kMinimalMachineConfig;
  text.replace(text.find("period_us = 75"), 14, "period_us = 75\nmax_feed_override = 3");
  auto bad = parse_machine_config(text, "m.toml");
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.error().message.find("max_feed_override"), std::string::npos);
}

// The modes every program starts in: the shipped machine blends (G64);
// anything that would move, dwell or switch the laser is refused with what
// is allowed.
TEST(MachineConfig, StartupCodeAdmitsModalCodesOnly) {
  auto m = load_machine_config(kShare + "/machines/default.toml");
  ASSERT_TRUE(m);
  EXPECT_NE(m->startup_code.find("G64"), std::string::npos) << m->startup_code;
  const auto with = [](const std::string& code) {
    std::string text = kMinimalMachineConfig;
    text.replace(text.find("period_us = 75"), 14, "period_us = 75\nstartup_code = \"" + code + "\"");
    return parse_machine_config(text, "m.toml");
  };
  auto ok = with("G17 g21 G90 G91.1 G94 G55 G64 P0.02 Q0.001 M5 M9");
  ASSERT_TRUE(ok) << ok.error().to_string();
  EXPECT_EQ(ok->startup_code, "G17 g21 G90 G91.1 G94 G55 G64 P0.02 Q0.001 M5 M9");
  for (const char* bad : {"G1 X10", "G64 M3", "G4 P1", "G61 P0.1", "G64 P11", "G64 Pabc", "M30", "F600"}) {
    auto r = with(bad);
    ASSERT_FALSE(r) << bad;
    EXPECT_NE(r.error().message.find("machine.startup_code"), std::string::npos) << r.error().message;
    EXPECT_NE(r.error().message.find("found '"), std::string::npos) << r.error().message;
  }
}

}  // namespace
}  // namespace lcnc

// Homing keys and the pitch-compensation table (optional per axis).
namespace lcnc {
namespace {

// kMinimalMachineConfig with `extra` appended to its [axes.X] table (the last one).
std::string with_x(const std::string& extra) { return std::string(kMinimalMachineConfig) + extra; }

TEST(MachineConfigHoming, DefaultsFollowTheAxis) {
  auto m = parse_machine_config(kMinimalMachineConfig, "m.toml");
  ASSERT_TRUE(m) << m.error().to_string();
  const AxisConfig& x = m->axis(Axis::X);
  EXPECT_FALSE(x.home_position.has_value());
  EXPECT_DOUBLE_EQ(x.home_position_or_default(), 0.0);           // min
  EXPECT_DOUBLE_EQ(x.home_search_velocity_or_default(), -15.0);  // −0.1 · 150
  EXPECT_DOUBLE_EQ(x.home_latch_velocity_or_default(), 1.5);     // |search| / 10
  EXPECT_TRUE(x.pitch_compensation.empty());
}

TEST(MachineConfigHoming, DefaultLatchFollowsAGivenSearchVelocity) {
  auto m = parse_machine_config(with_x("home_search_velocity = 40\n"), "m.toml");
  ASSERT_TRUE(m) << m.error().to_string();
  EXPECT_DOUBLE_EQ(m->axis(Axis::X).home_search_velocity_or_default(), 40.0);
  EXPECT_DOUBLE_EQ(m->axis(Axis::X).home_latch_velocity_or_default(), 4.0);
}

TEST(MachineConfigHoming, GivenKeysAreRead) {
  auto m = parse_machine_config(
      with_x("home_position = 100\nhome_search_velocity = 20.5\nhome_latch_velocity = 0.5\n"), "m.toml");
  ASSERT_TRUE(m) << m.error().to_string();
  const AxisConfig& x = m->axis(Axis::X);
  EXPECT_DOUBLE_EQ(x.home_position_or_default(), 100.0);  // max is allowed
  EXPECT_DOUBLE_EQ(x.home_search_velocity_or_default(), 20.5);
  EXPECT_DOUBLE_EQ(x.home_latch_velocity_or_default(), 0.5);
}

TEST(MachineConfigHoming, DefaultMachineHomesEachAxis) {
  auto m = load_machine_config(kShare + "/machines/default.toml");
  ASSERT_TRUE(m) << m.error().to_string();
  for (Axis a : kAllAxes) {
    const AxisConfig& ax = m->axis(a);
    if (!ax.present) continue;
    EXPECT_TRUE(ax.home_position && ax.home_search_velocity && ax.home_latch_velocity)
        << letter(a) << ": home keys given explicitly";
  }
  EXPECT_DOUBLE_EQ(m->axis(Axis::X).home_search_velocity_or_default(), -50.0);
  EXPECT_DOUBLE_EQ(m->axis(Axis::Z).home_position_or_default(), 500.0);
  EXPECT_GT(m->axis(Axis::Z).home_search_velocity_or_default(), 0.0);  // Z homes up
  const PitchTable& t = m->axis(Axis::X).pitch_compensation;
  ASSERT_EQ(t.values.size(), 11u);
  EXPECT_DOUBLE_EQ(t.start, 0.0);
  EXPECT_DOUBLE_EQ(t.end(), 1000.0);
  EXPECT_TRUE(m->axis(Axis::Y).pitch_compensation.empty());
}

// Each bad value is rejected with the key, the value and the allowed range.
TEST(MachineConfigHoming, RangeChecksNameKeyValueAndRange) {
  struct Case {
    const char* extra;
    const char* key_and_value;
    const char* range;
  };
  const Case cases[] = {
      {"home_position = 150\n", "axes.X.home_position = 150", "0 … 100"},
      {"home_position = -0.5\n", "axes.X.home_position = -0.5", "0 … 100"},
      {"home_search_velocity = 0\n", "axes.X.home_search_velocity = 0", "-150 … 150"},
      {"home_search_velocity = -151\n", "axes.X.home_search_velocity = -151", "-150 … 150"},
      {"home_latch_velocity = 0\n", "axes.X.home_latch_velocity = 0", "> 0 … 15"},
      {"home_latch_velocity = -1\n", "axes.X.home_latch_velocity = -1", "> 0 … 15"},
      {"home_latch_velocity = 16\n", "axes.X.home_latch_velocity = 16", "> 0 … 15"},
      {"home_search_velocity = 4\nhome_latch_velocity = 5\n", "axes.X.home_latch_velocity = 5", "> 0 … 4"},
  };
  for (const Case& c : cases) {
    auto m = parse_machine_config(with_x(c.extra), "m.toml");
    ASSERT_FALSE(m) << c.extra;
    EXPECT_EQ(m.error().code, ErrorCode::ConfigBadValue) << c.extra;
    EXPECT_NE(m.error().message.find(c.key_and_value), std::string::npos)
        << c.extra << " -> " << m.error().message;
    EXPECT_NE(m.error().message.find(c.range), std::string::npos) << c.extra << " -> " << m.error().message;
  }
}

// Real drives (lasercncd --hal): the following-error limit per axis (0, the
// default, is not checked; up to the axis's travel) and the switch that lets
// a machine without home switches run unhomed.
TEST(MachineConfigHoming, FollowingErrorAndAllowUnhomedAreReadAndChecked) {
  auto plain = parse_machine_config(kMinimalMachineConfig, "m.toml");
  ASSERT_TRUE(plain);
  EXPECT_EQ(plain->axes[0].following_error, 0.0);
  EXPECT_FALSE(plain->allow_unhomed);
  std::string text = with_x("following_error = 0.25\n");
  text.replace(text.find("period_us = 75"), 14, "period_us = 75\nallow_unhomed = true");
  auto m = parse_machine_config(text, "m.toml");
  ASSERT_TRUE(m) << m.error().to_string();
  EXPECT_DOUBLE_EQ(m->axes[0].following_error, 0.25);
  EXPECT_TRUE(m->allow_unhomed);
  for (const char* bad : {"following_error = -1\n", "following_error = 101\n"}) {
    auto r = parse_machine_config(with_x(bad), "m.toml");
    ASSERT_FALSE(r) << bad;
    EXPECT_NE(r.error().message.find("axes.X.following_error"), std::string::npos) << r.error().message;
  }
  std::string typed = kMinimalMachineConfig;
  typed.replace(typed.find("period_us = 75"), 14, "period_us = 75\nallow_unhomed = 1");
  auto t = parse_machine_config(typed, "m.toml");
  ASSERT_FALSE(t);
  EXPECT_NE(t.error().message.find("allow_unhomed"), std::string::npos) << t.error().message;
}

// Block delete: on unless the machine says block_delete = false.
TEST(MachineConfig, BlockDeleteIsOnByDefaultAndReadAsABoolean) {
  auto plain = parse_machine_config(kMinimalMachineConfig, "m.toml");
  ASSERT_TRUE(plain);
  EXPECT_TRUE(plain->block_delete);
  std::string text = kMinimalMachineConfig;
  text.replace(text.find("period_us = 75"), 14, "period_us = 75\nblock_delete = false");
  auto m = parse_machine_config(text, "m.toml");
  ASSERT_TRUE(m) << m.error().to_string();
  EXPECT_FALSE(m->block_delete);
  std::string typed = kMinimalMachineConfig;
  typed.replace(typed.find("period_us = 75"), 14, "period_us = 75\nblock_delete = \"off\"");
  auto t = parse_machine_config(typed, "m.toml");
  ASSERT_FALSE(t);
  EXPECT_NE(t.error().message.find("block_delete"), std::string::npos) << t.error().message;
}

TEST(MachineConfig, SubroutinePathIsTakenFromTheConfigFilesFolder) {
  std::string text = kMinimalMachineConfig;
  text.replace(text.find("period_us = 75"), 14, "period_us = 75\nsubroutine_path = [\"subs\", \"/opt/ngc\"]");
  auto m = parse_machine_config(text, "/etc/lasercnc/m.toml");
  ASSERT_TRUE(m) << m.error().to_string();
  EXPECT_EQ(m->subroutine_path, (std::vector<std::string>{"/etc/lasercnc/subs", "/opt/ngc"}));
  std::string bad = kMinimalMachineConfig;
  bad.replace(bad.find("period_us = 75"), 14, "period_us = 75\nsubroutine_path = [\"subs\", 3]");
  auto b = parse_machine_config(bad, "m.toml");
  ASSERT_FALSE(b);
  EXPECT_NE(b.error().message.find("subroutine_path[1]"), std::string::npos) << b.error().message;
}

// The HAL example machines (share/hal/*/machine.toml) load, check their
// following errors and start unhomed unless they say otherwise.
TEST(MachineConfigHoming, TheHalExampleMachinesLoad) {
  for (const char* dir : {"sim", "parport", "mesa-7i76e"}) {
    auto m = load_machine_config(kShare + "/hal/" + dir + "/machine.toml");
    ASSERT_TRUE(m) << dir << ": " << m.error().to_string();
    EXPECT_EQ(m->period_ns, 1'000'000u) << dir << ": a 1 ms servo thread";
    EXPECT_FALSE(m->allow_unhomed) << dir;
    for (const AxisConfig& a : m->axes)
      if (a.present) {
        EXPECT_GT(a.following_error, 0.0) << dir;
      }
  }
}

TEST(MachineConfigHoming, WrongTypeAndMisspeltKeyAreErrors) {
  auto m = parse_machine_config(with_x("home_position = \"left\"\n"), "m.toml");
  ASSERT_FALSE(m);
  EXPECT_EQ(m.error().code, ErrorCode::ConfigBadValue);
  EXPECT_NE(m.error().message.find("'axes.X.home_position' must be a number"), std::string::npos);

  auto typo = parse_machine_config(with_x("home_serch_velocity = -5\n"), "m.toml");
  ASSERT_FALSE(typo);
  EXPECT_EQ(typo.error().code, ErrorCode::ConfigUnknownKey);
  EXPECT_NE(typo.error().message.find("axes.X.home_serch_velocity"), std::string::npos);
}

// A --vmax below the default search speed keeps the defaults consistent: they
// are derived from max_velocity when asked for, not frozen at load.
TEST(MachineConfigHoming, DefaultsFollowAChangedMaxVelocity) {
  auto m = parse_machine_config(kMinimalMachineConfig, "m.toml");
  ASSERT_TRUE(m);
  m->axis(Axis::X).max_velocity = 10.0;
  EXPECT_TRUE(validate(*m));
  EXPECT_DOUBLE_EQ(m->axis(Axis::X).home_search_velocity_or_default(), -1.0);
}

const char* kPitch = "[axes.X.pitch_compensation]\nstart = 10\ninterval = 20\n";

TEST(MachineConfigPitch, TableIsRead) {
  auto m = parse_machine_config(with_x(std::string(kPitch) + "values = [0, 0.01, -0.02, 1]\n"), "m.toml");
  ASSERT_TRUE(m) << m.error().to_string();
  const PitchTable& t = m->axis(Axis::X).pitch_compensation;
  EXPECT_DOUBLE_EQ(t.start, 10.0);
  EXPECT_DOUBLE_EQ(t.interval, 20.0);
  ASSERT_EQ(t.values.size(), 4u);
  EXPECT_DOUBLE_EQ(t.values[2], -0.02);
  EXPECT_DOUBLE_EQ(t.values[3], 1.0);  // integers count as numbers; 1.0 is the bound
  EXPECT_DOUBLE_EQ(t.end(), 70.0);
}

TEST(MachineConfigPitch, BadTablesNameKeyValueAndRange) {
  struct Case {
    std::string toml;
    ErrorCode code;
    const char* expect;
    const char* range;
  };
  const std::string p = kPitch;
  const Case cases[] = {
      {p + "values = [0]\n", ErrorCode::ConfigBadValue, "axes.X.pitch_compensation.values has 1",
       "2 or more"},
      {p + "values = []\n", ErrorCode::ConfigBadValue, "axes.X.pitch_compensation.values has 0", "2 or more"},
      {p + "values = [0, 0.5, 1.5]\n", ErrorCode::ConfigBadValue, "axes.X.pitch_compensation.values[2] = 1.5",
       "-1 … 1 mm"},
      {p + "values = [0, -1.01]\n", ErrorCode::ConfigBadValue, "axes.X.pitch_compensation.values[1] = -1.01",
       "-1 … 1 mm"},
      {"[axes.X.pitch_compensation]\nstart = 0\ninterval = 0\nvalues = [0, 0]\n", ErrorCode::ConfigBadValue,
       "axes.X.pitch_compensation.interval = 0", "> 0"},
      {"[axes.X.pitch_compensation]\nstart = 0\ninterval = -5\nvalues = [0, 0]\n", ErrorCode::ConfigBadValue,
       "axes.X.pitch_compensation.interval = -5", "> 0"},
      // 10 + 5·20 = 110 > max 100
      {p + "values = [0, 0, 0, 0, 0, 0]\n", ErrorCode::ConfigBadValue, "10 … 110", "min … max = 0 … 100"},
      {"[axes.X.pitch_compensation]\nstart = -1\ninterval = 1\nvalues = [0, 0]\n", ErrorCode::ConfigBadValue,
       "-1 … 0", "min … max = 0 … 100"},
      {p + "values = 0.1\n", ErrorCode::ConfigBadValue,
       "'axes.X.pitch_compensation.values' must be an array of numbers", ""},
      {p + "values = [0, \"a\"]\n", ErrorCode::ConfigBadValue,
       "'axes.X.pitch_compensation.values[1]' must be a number", ""},
      {p + "values = [0, 0]\nstep = 1\n", ErrorCode::ConfigUnknownKey, "axes.X.pitch_compensation.step",
       "start, interval, values"},
      {"[axes.X.pitch_compensation]\nstart = 0\nvalues = [0, 0]\n", ErrorCode::ConfigMissingKey,
       "axes.X.pitch_compensation.interval", ""},
      {"pitch_compensation = 3\n", ErrorCode::ConfigBadValue, "'axes.X.pitch_compensation' must be a table",
       ""},
  };
  for (const Case& c : cases) {
    auto m = parse_machine_config(with_x(c.toml), "m.toml");
    ASSERT_FALSE(m) << c.toml;
    EXPECT_EQ(m.error().code, c.code) << c.toml << " -> " << m.error().message;
    EXPECT_NE(m.error().message.find(c.expect), std::string::npos) << c.toml << " -> " << m.error().message;
    EXPECT_NE(m.error().message.find(c.range), std::string::npos) << c.toml << " -> " << m.error().message;
  }
}

// validate() checks a table built in code the same way as one loaded.
TEST(MachineConfigPitch, ValidateChecksATableBuiltInCode) {
  auto m = parse_machine_config(kMinimalMachineConfig, "m.toml");
  ASSERT_TRUE(m);
  m->axis(Axis::X).pitch_compensation = PitchTable{0.0, 10.0, {0.01}};
  Status one = validate(*m);
  ASSERT_FALSE(one);
  EXPECT_NE(one.error().message.find("values has 1 value(s)"), std::string::npos);
  m->axis(Axis::X).pitch_compensation = PitchTable{0.0, 10.0, {0.01, -0.01}};
  EXPECT_TRUE(validate(*m));
}

// start + (n−1)·interval = 0 + 12·0.1 is 1.2000000000000002 in doubles: a
// table written to end on max must not be refused for that.
TEST(MachineConfigPitch, EndOnMaxSurvivesRounding) {
  std::string text = kMinimalMachineConfig;
  text.replace(text.find("max = 100"), 9, "max = 1.2");
  text +=
      "[axes.X.pitch_compensation]\nstart = 0\ninterval = 0.1\n"
      "values = [0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0]\n";
  auto m = parse_machine_config(text, "m.toml");
  ASSERT_TRUE(m) << m.error().to_string();
  EXPECT_GT(m->axis(Axis::X).pitch_compensation.end(), 1.2);  // the case is real
}

// Seed preset: 15 pulses per period; 150 mm/s needs 11.25. With slope s the
// kernel may output 11.25·(1 + s) + 1: s = 0.2 fits (14.5), s = 0.3 does not
// (15.625).
TEST(MachineConfigPitch, SlopeMustFitTheDdaPreset) {
  auto too_big = parse_machine_config(with_x(std::string(kPitch) + "values = [0, 4]\n"), "m.toml");
  ASSERT_FALSE(too_big);  // |4| > 1: the value check comes first
  EXPECT_NE(too_big.error().message.find("values[1] = 4"), std::string::npos);
  auto fits = parse_machine_config(
      with_x("[axes.X.pitch_compensation]\nstart = 0\ninterval = 1\nvalues = [0, 0.2, 0]\n"), "m.toml");
  ASSERT_TRUE(fits) << fits.error().to_string();
  EXPECT_NEAR(fits->axis(Axis::X).pitch_compensation.max_slope(), 0.2, 1e-12);
  auto steep = parse_machine_config(
      with_x("[axes.X.pitch_compensation]\nstart = 0\ninterval = 1\nvalues = [0, 0.3, 0]\n"), "m.toml");
  ASSERT_FALSE(steep);
  EXPECT_NE(steep.error().message.find("axes.X.pitch_compensation.values: slope 0.3"), std::string::npos)
      << steep.error().message;
  EXPECT_NE(steep.error().message.find("15.625"), std::string::npos) << steep.error().message;
}

TEST(PitchTable, InterpolatesAndHoldsTheEnds) {
  const PitchTable t{10.0, 20.0, {0.0, 0.02, -0.02}};
  EXPECT_DOUBLE_EQ(t.at(-100.0), 0.0);
  EXPECT_DOUBLE_EQ(t.at(10.0), 0.0);
  EXPECT_DOUBLE_EQ(t.at(20.0), 0.01);
  EXPECT_DOUBLE_EQ(t.at(30.0), 0.02);
  EXPECT_DOUBLE_EQ(t.at(35.0), 0.01);
  EXPECT_DOUBLE_EQ(t.at(50.0), -0.02);
  EXPECT_DOUBLE_EQ(t.at(1e9), -0.02);
  EXPECT_DOUBLE_EQ(t.max_slope(), 0.002);
  const PitchTable s = t.scaled(1000.0);
  EXPECT_DOUBLE_EQ(s.start, 10'000.0);
  EXPECT_DOUBLE_EQ(s.interval, 20'000.0);
  EXPECT_DOUBLE_EQ(s.at(20'000.0), 10.0);
  EXPECT_DOUBLE_EQ(s.max_slope(), t.max_slope());
  EXPECT_DOUBLE_EQ(PitchTable{}.at(5.0), 0.0);
  EXPECT_DOUBLE_EQ(PitchTable{}.max_slope(), 0.0);
}

}  // namespace
}  // namespace lcnc

// A config built in code has zero work offsets, whatever the memory held
// before (an Eigen matrix is not zeroed by `{}`).
TEST(MachineConfigDefaults, WorkOffsetsStartAtZero) {
  alignas(lcnc::MachineConfig) unsigned char storage[sizeof(lcnc::MachineConfig)];
  std::memset(storage, 0xA5, sizeof storage);
  auto* m = new (storage) lcnc::MachineConfig();
  for (const lcnc::Pose& p : m->work_offsets) EXPECT_TRUE(p.isZero());
  m->~MachineConfig();
}

#include "machine/machine_config.h"

#include <gtest/gtest.h>

#include <string>

namespace lcnc {
namespace {

const std::string kShare = std::string(LCNC_SOURCE_DIR) + "/share";

const char* kMinimal = R"(
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
  auto m = parse_machine_config(kMinimal, "seed.toml");
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
  std::string text = kMinimal;
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
  std::string text = kMinimal;
  text.replace(text.find("max = 100"), 9, "max = \"100\"");
  auto m = parse_machine_config(text, "m.toml");
  ASSERT_FALSE(m);
  EXPECT_EQ(m.error().code, ErrorCode::ConfigBadValue);
  EXPECT_NE(m.error().message.find("axes.X.max"), std::string::npos);
}

TEST(MachineConfig, VelocityBeyondDdaPresetIsRejectedWithTheNumbers) {
  std::string text = kMinimal;
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
    std::string text = kMinimal;
    const auto at = text.find(c.from);
    ASSERT_NE(at, std::string::npos) << c.from;
    text.replace(at, std::string(c.from).size(), c.to);
    auto m = parse_machine_config(text, "m.toml");
    ASSERT_FALSE(m) << c.to;
    EXPECT_EQ(m.error().code, ErrorCode::ConfigBadValue) << c.to;
    EXPECT_NE(m.error().message.find(c.expect), std::string::npos)
        << c.to << " -> " << m.error().message;
  }
}

TEST(MachineConfig, WrapOnlyOnRotaryAxesSpanning360) {
  std::string text = kMinimal;
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
      "[axes.A]\ntype = \"linear\"\nmin = 0\nmax = 10\nmax_velocity = 1\nmax_acceleration = 1\n",
      "m.toml");
  ASSERT_FALSE(m);
  EXPECT_NE(m.error().message.find("must be \"rotary\""), std::string::npos);
}

TEST(MachineConfig, WorkOffsetsNeedSixNumbers) {
  std::string text = kMinimal;
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
  std::string text = kMinimal;
  text.replace(text.find("period_us = 75"), 14, "period_us = 75\nmax_feed_override = 3");
  auto bad = parse_machine_config(text, "m.toml");
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.error().message.find("max_feed_override"), std::string::npos);
}

}  // namespace
}  // namespace lcnc

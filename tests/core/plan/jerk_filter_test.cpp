#include "plan/jerk_filter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "core/plan/test_machine.h"
#include "plan/tolerances.h"

namespace lcnc {
namespace {

// --- machine.max_jerk in the config -----------------------------------------

const char* kMachine = R"([machine]
period_us = 75
%s
[axes.X]
min = 0
max = 100
max_velocity = 100
max_acceleration = 1000
)";

Result<MachineConfig> parse_with(const std::string& line) {
  char text[512];
  std::snprintf(text, sizeof text, kMachine, line.c_str());
  return parse_machine_config(text, "jerk.toml");
}

TEST(MaxJerkKey, AbsentMeansNoJerkLimit) {
  auto m = parse_with("");
  ASSERT_TRUE(m) << m.error().to_string();
  EXPECT_EQ(m->max_jerk, 0.0);
  EXPECT_FALSE(jerk_limit(*m).enabled());
}

TEST(MaxJerkKey, IsReadInMmPerCubicSecond) {
  auto m = parse_with("max_jerk = 50000");
  ASSERT_TRUE(m) << m.error().to_string();
  EXPECT_EQ(m->max_jerk, 50000.0);
  EXPECT_TRUE(jerk_limit(*m).enabled());
}

// 0 is "none", as in a config built in code: the key has one range.
TEST(MaxJerkKey, ZeroMeansNoJerkLimit) {
  auto m = parse_with("max_jerk = 0");
  ASSERT_TRUE(m) << m.error().to_string();
  EXPECT_FALSE(jerk_limit(*m).enabled());
}

TEST(MaxJerkKey, NegativeOrOutOfRangeIsAnErrorWithItsPlace) {
  for (const char* v : {"-5", "0.5", "2e10"}) {
    auto m = parse_with(std::string("max_jerk = ") + v);
    ASSERT_FALSE(m) << v;
    EXPECT_EQ(m.error().code, ErrorCode::ConfigBadValue);
    EXPECT_NE(m.error().message.find("machine.max_jerk = "), std::string::npos) << v;
    EXPECT_NE(m.error().message.find("allowed 1 … 1e+10 mm/s³"), std::string::npos) << m.error().message;
    EXPECT_EQ(m.error().line, 3u);
    EXPECT_GT(m.error().col, 0u);
  }
}

TEST(MaxJerkKey, MustBeANumber) {
  auto m = parse_with("max_jerk = \"fast\"");
  ASSERT_FALSE(m);
  EXPECT_EQ(m.error().code, ErrorCode::ConfigBadValue);
  EXPECT_NE(m.error().message.find("'machine.max_jerk' must be a number"), std::string::npos);
}

TEST(MaxJerkKey, ValidateAcceptsZeroAndRejectsNonsense) {
  auto m = testing::test_machine();
  EXPECT_TRUE(validate(m));  // 0: no limit (a config built in code)
  m.max_jerk = 5e4;
  EXPECT_TRUE(validate(m));
  for (double bad : {-1.0, 0.5, 1e11, std::nan("")}) {
    m.max_jerk = bad;
    const Status s = validate(m);
    ASSERT_FALSE(s) << bad;
    EXPECT_NE(s.error().message.find("machine.max_jerk"), std::string::npos);
  }
}

// --- the filter's parameters ----------------------------------------------

// e_f of a window, eq. (2) of jerk_filter.h, for the test machine's three
// equal linear axes.
double error_of(const MachineConfig& m, std::uint32_t taps, double a) {
  const double T = m.period_s();
  return std::sqrt(3.0) * a * T * T * (double(taps) * taps - 1.0) / 24.0;
}

TEST(JerkLimit, WindowFromJerkWhenTheToleranceAllowsFullAcceleration) {
  auto m = testing::test_machine(150.0, 3000.0);
  m.max_jerk = 2e6;  // 2000 m/s³
  const JerkLimit l = jerk_limit(m);
  const double swing = 2.0 + plan::kJunctionJumpShare;  // K_max = 1
  EXPECT_EQ(l.taps, static_cast<std::uint32_t>(std::ceil(swing * 3000.0 / (2e6 * m.period_s()))));
  EXPECT_EQ(l.accel_scale, 1.0);
  EXPECT_NEAR(l.error_mm, error_of(m, l.taps, 3000.0), 1e-15);
  EXPECT_LT(l.error_mm, 0.5 * m.path_tolerance_mm);
  // the jerk bound of eq. (1) holds with the window found
  EXPECT_LE(swing * 3000.0 / (l.taps * m.period_s()), 2e6);
}

TEST(JerkLimit, LowersAccelerationToKeepHalfTheTolerance) {
  auto m = testing::test_machine(150.0, 3000.0);
  m.max_jerk = 1e5;  // 100 m/s³: full acceleration would deviate by ~0.9 mm
  const JerkLimit l = jerk_limit(m);
  ASSERT_TRUE(l.enabled());
  const double a = l.accel_scale * 3000.0;
  const double swing = 2.0 + plan::kJunctionJumpShare;
  EXPECT_LT(l.accel_scale, 1.0);
  EXPECT_LE(swing * a / (l.taps * m.period_s()), 1e5 * (1 + 1e-12));  // jerk within J
  EXPECT_NEAR(l.error_mm, error_of(m, l.taps, a), 1e-15);
  EXPECT_LE(l.error_mm, 0.5 * m.path_tolerance_mm);
  // the largest window that fits: one more tap would be over the budget
  const double a_next = 1e5 * (l.taps + 1) * m.period_s() / swing;
  EXPECT_GT(error_of(m, l.taps + 1, a_next), 0.5 * m.path_tolerance_mm);
  const MachineConfig p = planned_machine(m, l);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(p.axes[i].max_acceleration, a);
  EXPECT_EQ(p.axis(Axis::C).max_acceleration, 3600.0);  // rotary axes keep theirs
}

// The operator's highest override is no derate: the window is the one the
// machine's own acceleration and jerk ask for (the RT runs the plan at
// K ≤ 1, where the jerk is K³·J of the plan's).
TEST(JerkLimit, PlansAtTheMachinesLimitsWhateverTheHighestOverride) {
  auto m = testing::test_machine(150.0, 3000.0);
  m.max_jerk = 2e6;
  const JerkLimit at_one = jerk_limit(m);
  m.max_feed_override = 1.5;
  const JerkLimit l = jerk_limit(m);
  const double swing = 2.0 + plan::kJunctionJumpShare;
  EXPECT_EQ(l.taps, static_cast<std::uint32_t>(std::ceil(swing * 3000.0 / (2e6 * m.period_s()))));
  EXPECT_EQ(l.taps, at_one.taps);
  EXPECT_EQ(l.accel_scale, at_one.accel_scale);
}

TEST(JerkLimit, OffWhenTheTrapezoidsAlreadyKeepTheJerk) {
  auto m = testing::test_machine(150.0, 3000.0);
  m.max_jerk = 1e10;  // 2.1·a/T = 8.4e7 < J: one tap
  EXPECT_FALSE(jerk_limit(m).enabled());
  const MachineConfig p = planned_machine(m, jerk_limit(m));
  EXPECT_EQ(p.axes[0].max_acceleration, 3000.0);
}

// --- the moving average ---------------------------------------------------

PeriodSample sample_jerk_filter(double x, std::uint32_t line, float power = 0.0f) {
  PeriodSample s;
  s.pose = Pose::Zero();
  s.pose[0] = x;
  s.line = line;
  s.power_pct = power;
  s.kind = MotionKind::Linear;
  return s;
}

TEST(JerkFilter, AveragesPosesAndDelaysTheRestByHalfTheWindow) {
  JerkFilter f(5);
  std::vector<double> in = {1.0};  // the first sample fills the window
  EXPECT_EQ(f.filter(sample_jerk_filter(1.0, 0)).pose[0], 1.0);
  for (std::uint32_t k = 1; k < 40; ++k) {
    const double x = 1.0 + 0.25 * k * k;  // constant acceleration
    in.push_back(x);
    const PeriodSample out = f.filter(sample_jerk_filter(x, k));
    double mean = 0.0;
    for (int j = 0; j < 5; ++j) mean += in[std::max<int>(0, static_cast<int>(in.size()) - 1 - j)];
    mean /= 5.0;
    EXPECT_NEAR(out.pose[0], mean, 1e-12) << k;
    EXPECT_EQ(out.line, k >= 2 ? k - 2 : 0u) << k;  // the window's centre
    if (k >= 4) {
      // eq. (2): the mean of a parabola lies a·T²(M² − 1)/24 off its centre
      // (a = 0.5 per period², M = 5)
      const double centre = 1.0 + 0.25 * (k - 2.0) * (k - 2.0);
      EXPECT_NEAR(out.pose[0] - centre, 0.5 * (25.0 - 1.0) / 24.0, 1e-9);
    }
  }
}

TEST(JerkFilter, ConstantWindowGivesThePoseItself) {
  JerkFilter f(7);
  (void)f.filter(sample_jerk_filter(0.0, 0));
  for (int k = 1; k < 100; ++k) (void)f.filter(sample_jerk_filter(0.1 * k + 1e-7 / 3.0, 0));
  const double stop = 12.345678901234567;
  PeriodSample out;
  for (int k = 0; k < 7; ++k) out = f.filter(sample_jerk_filter(stop, 0));
  EXPECT_EQ(out.pose[0], stop);  // exact, whatever the running sum's rounding
}

TEST(JerkFilter, DynamicPowerIsTheWindowsMeanAndDarkAtRest) {
  JerkFilter f(4);
  auto m4 = [](double x, float p) {
    PeriodSample s = sample_jerk_filter(x, 0, p);
    s.power_cap_pct = 80.0f;
    s.speed = p;  // any speed: only its being 0 or not matters
    return s;
  };
  (void)f.filter(m4(0.0, 0.0f));
  EXPECT_FLOAT_EQ(f.filter(m4(1.0, 40.0f)).power_pct, 10.0f);
  EXPECT_FLOAT_EQ(f.filter(m4(2.0, 80.0f)).power_pct, 30.0f);
  for (int k = 0; k < 3; ++k) (void)f.filter(m4(3.0, 0.1f));
  PeriodSample out;
  for (int k = 0; k < 4; ++k) out = f.filter(m4(3.0, 0.0f));
  EXPECT_EQ(out.power_pct, 0.0f);  // exactly dark, not 1e-9 %
  EXPECT_EQ(out.speed, 0.0);
}

}  // namespace
}  // namespace lcnc

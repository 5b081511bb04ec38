#include "plan/motion_check.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "test_machine.h"

namespace lcnc {
namespace {

// x(t) of a rest-to-rest move of `dist` at speed v and acceleration a
// (a trapezoid, or a triangle when too short), mm.
struct Move {
  double dist, v, a;
  [[nodiscard]] double t_acc() const { return std::min(v / a, std::sqrt(dist / a)); }
  [[nodiscard]] double v_top() const { return a * t_acc(); }
  [[nodiscard]] double t_cruise() const { return (dist - a * t_acc() * t_acc()) / v_top(); }
  [[nodiscard]] double duration() const { return 2 * t_acc() + t_cruise(); }
  [[nodiscard]] double at(double t) const {
    const double ta = t_acc(), tc = t_cruise(), vt = v_top();
    if (t <= 0) return 0;
    if (t < ta) return 0.5 * a * t * t;
    if (t < ta + tc) return 0.5 * a * ta * ta + vt * (t - ta);
    const double td = std::min(t, duration()) - ta - tc;
    return 0.5 * a * ta * ta + vt * tc + vt * td - 0.5 * a * td * td;
  }
};

using testing::at_x;

// Runs `move` on X from 100 mm through a check, periods of T/K with K drawn
// in [0.3, 1.5] (a feed override that changes), positions rounded to steps.
MotionCheck run_motion_check(const MachineConfig& m, const Move& move, std::mt19937& rng,
                             bool vary_k = true) {
  const std::int64_t x0 = 100'000;
  MotionCheck check(m, at_x(x0));
  std::uniform_real_distribution<double> k(0.3, 1.5);
  double t = 0;
  std::int64_t t_ns = 0;
  while (t < move.duration()) {
    const double len_ns = vary_k ? std::round(m.period_ns / k(rng)) : m.period_ns;
    t_ns += static_cast<std::int64_t>(len_ns);
    t = static_cast<double>(t_ns) * 1e-9;
    check.add(t_ns, at_x(x0 + std::llround(move.at(t) * 1000.0)), 3);
  }
  check.finish();
  return check;
}

TEST(MotionCheck, WindowsBringQuantizationUnderTheirShareOfTheLimits) {
  const MachineConfig m = testing::test_machine();
  const MotionCheck c(m, {});
  const double T = 75e-6, q = 1e-3;
  // velocity: q/(W·T) ≤ 2 % of 360 deg/s (C, the smallest), the fewest W
  EXPECT_LE(q / (c.velocity_window() * T), 0.02 * 360.0);
  EXPECT_GT(q / ((c.velocity_window() - 1) * T), 0.02 * 360.0);
  // acceleration: 2q/(W·T)² ≤ 5 % of 3600 deg/s² (C)
  const double h = c.acceleration_window() * T, h1 = (c.acceleration_window() - 1) * T;
  EXPECT_LE(2 * q / (h * h), 0.05 * 3600.0);
  EXPECT_GT(2 * q / (h1 * h1), 0.05 * 3600.0);
}

// Fixed-seed property: moves within the limits, quantized, at an override
// that changes every period, never read as a breach.
TEST(MotionCheck, MotionWithinItsLimitsPassesWhateverTheQuantizationAndOverride) {
  const MachineConfig m = testing::test_machine();
  std::mt19937 rng(19);
  std::uniform_real_distribution<double> dist(0.001, 40.0), share(0.5, 1.0);
  for (int n = 0; n < 200; ++n) {
    // the override scales speed by K and acceleration by K²: plan for 1.5
    const Move move{dist(rng), 500.0 / 1.5 * share(rng), 5000.0 / 2.25 * share(rng)};
    const MotionCheck c = run_motion_check(m, move, rng);
    ASSERT_TRUE(c.ok()) << n << ": " << c.breaches().front();
    EXPECT_LE(c.axes()[0].velocity.peak, 500.0 + c.axes()[0].velocity.quantization);
  }
  // and at full limits without override: the peaks come close to them
  const MotionCheck c = run_motion_check(m, Move{100.0, 500.0, 5000.0}, rng, false);
  EXPECT_TRUE(c.ok());
  EXPECT_GT(c.axes()[0].velocity.peak, 490.0);
  EXPECT_GT(c.axes()[0].acceleration.peak, 4500.0);
}

TEST(MotionCheck, ThreePercentTooFastIsAVelocityBreach) {
  const MachineConfig m = testing::test_machine();
  std::mt19937 rng(1);
  const MotionCheck c = run_motion_check(m, Move{200.0, 515.0, 4000.0}, rng, false);
  ASSERT_FALSE(c.ok());
  EXPECT_GT(c.axes()[0].velocity.excess, 0.0);
  EXPECT_EQ(c.axes()[0].acceleration.excess, 0.0);
  ASSERT_EQ(c.breaches().size(), 1u);
  EXPECT_NE(c.breaches()[0].find("axis X velocity 5"), std::string::npos) << c.breaches()[0];
  EXPECT_NE(c.breaches()[0].find("at line 3"), std::string::npos) << c.breaches()[0];
}

TEST(MotionCheck, TenPercentTooMuchAccelerationIsAnAccelerationBreach) {
  const MachineConfig m = testing::test_machine();
  std::mt19937 rng(1);
  const MotionCheck c = run_motion_check(m, Move{200.0, 400.0, 5500.0}, rng, false);
  ASSERT_FALSE(c.ok());
  EXPECT_EQ(c.axes()[0].velocity.excess, 0.0);
  EXPECT_GT(c.axes()[0].acceleration.excess, 0.0);
}

// What a dropped segment did: X from rest at 255 steps a period for 39
// periods (3400 mm/s), then on.
TEST(MotionCheck, AJumpIsABreachOfBoth) {
  const MachineConfig m = testing::test_machine();
  MotionCheck c(m, at_x(0));
  std::int64_t x = 0;
  for (int k = 1; k <= 39; ++k) c.add(k * 75'000, at_x(x += 255), 2);
  for (int k = 40; k <= 200; ++k) c.add(k * 75'000, at_x(x), 2);
  c.finish();
  ASSERT_FALSE(c.ok());
  EXPECT_GT(c.axes()[0].velocity.peak, 3000.0);
  EXPECT_GT(c.axes()[0].velocity.excess, 0.0);
  EXPECT_GT(c.axes()[0].acceleration.excess, 0.0);
  EXPECT_EQ(c.axes()[0].velocity.line, 2u);
}

// The first period far from where the job started: a jump at the start.
TEST(MotionCheck, StartingAwayFromTheStartIsAJump) {
  const MachineConfig m = testing::test_machine();
  MotionCheck c(m, at_x(0));
  for (int k = 1; k <= 200; ++k) c.add(k * 75'000, at_x(1000), 1);
  c.finish();
  EXPECT_FALSE(c.ok());
}

// Cruising at 400 mm/s when the trace ends: the axes stop dead after it.
TEST(MotionCheck, EndingAtSpeedIsCaughtWhenTheAxesComeToRest) {
  const MachineConfig m = testing::test_machine();
  const Move move{100.0, 400.0, 4000.0};
  MotionCheck c(m, at_x(0));
  for (std::int64_t k = 1; k * 75e-6 < 0.15; ++k)  // speeding up ends at 0.1 s
    c.add(k * 75'000, at_x(std::llround(move.at(k * 75e-6) * 1000.0)), 1);
  EXPECT_TRUE(c.ok());
  c.finish();
  EXPECT_FALSE(c.ok());
  EXPECT_GT(c.axes()[0].acceleration.excess, 0.0);
}

// Lost records: no window spans the gap (it would read the motion in
// between as one period's), and the gap is counted.
TEST(MotionCheck, NoWindowSpansAGap) {
  const MachineConfig m = testing::test_machine();
  MotionCheck c(m, at_x(0));
  for (int k = 1; k <= 200; ++k) c.add(75'000LL * k, at_x(0), 1);
  c.gap();
  for (int k = 1000; k <= 1200; ++k) c.add(75'000LL * k, at_x(5000), 1);
  EXPECT_TRUE(c.ok());
  EXPECT_EQ(c.gaps(), 1u);
}

}  // namespace
}  // namespace lcnc

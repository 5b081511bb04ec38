#include "rt/feed_override.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace lcnc::rt {
namespace {

// The default machine's figures (share/machines/default.toml).
MachineConfig default_like() {
  MachineConfig m;
  m.period_ns = 75'000;
  m.max_feed_override = 1.5;
  const double v[5] = {500, 500, 250, 180, 360};
  const double a[5] = {5000, 5000, 3000, 1800, 3600};
  const int idx[5] = {0, 1, 2, 3, 5};  // X Y Z A C
  for (int k = 0; k < 5; ++k) {
    AxisConfig& ax = m.axes[idx[k]];
    ax.present = true;
    ax.axis = static_cast<Axis>(idx[k]);
    ax.max_velocity = v[k];
    ax.max_acceleration = a[k];
  }
  return m;
}

TEST(FeedOverrideRamp, RateAndKMinFollowTheMachine) {
  const FeedOverrideRamp r(default_like());
  // ρ = s·K_max·min(amax/vmax) = 1/3 · 1.5 · 10 /s
  EXPECT_DOUBLE_EQ(r.rate_per_s(), 5.0);
  EXPECT_DOUBLE_EQ(r.k_min(), std::sqrt(5.0 * 75e-6));
  EXPECT_DOUBLE_EQ(r.k_max(), 1.5);
  // the axis with the least acceleration per speed sets the rate
  MachineConfig heavy = default_like();
  heavy.axes[1].max_acceleration = 500;  // Y: 1 /s
  EXPECT_DOUBLE_EQ(FeedOverrideRamp(heavy).rate_per_s(), 0.5);
  // absent axes do not count
  heavy.axes[1].present = false;
  EXPECT_DOUBLE_EQ(FeedOverrideRamp(heavy).rate_per_s(), 5.0);
}

TEST(FeedOverrideRamp, TargetIsClampedToHoldOrTheRunnableRange) {
  const FeedOverrideRamp r(default_like());
  EXPECT_EQ(r.clamp_target(std::numeric_limits<double>::quiet_NaN()), 0.0);
  EXPECT_EQ(r.clamp_target(-1.0), 0.0);
  EXPECT_EQ(r.clamp_target(0.0), 0.0);
  EXPECT_EQ(r.clamp_target(1e-6), r.k_min());
  EXPECT_EQ(r.clamp_target(1.0), 1.0);
  EXPECT_EQ(r.clamp_target(2.0), 1.5);
  EXPECT_EQ(r.clamp_target(std::numeric_limits<double>::infinity()), 1.5);
  EXPECT_TRUE(r.holds(0.0));
  EXPECT_TRUE(r.holds(r.k_min() * 0.999));
  EXPECT_FALSE(r.holds(r.k_min()));
}

// Runs the ramp as the kernel does: each period lasts T/K (T while held),
// then K steps toward the target. Returns K per period and the machine time
// at the start of each period.
struct Ramped {
  std::vector<double> k;
  std::vector<double> t_start_s;
};
Ramped run_ramp(const FeedOverrideRamp& r, double period_s, double k0, double target,
                std::size_t periods) {
  Ramped out;
  double k = k0, t = 0.0;
  for (std::size_t i = 0; i < periods; ++i) {
    out.k.push_back(k);
    out.t_start_s.push_back(t);
    const double len = r.holds(k) ? period_s : period_s / k;
    t += len;
    k = r.step(k, target, len);
  }
  return out;
}

TEST(FeedOverrideRamp, RisesLinearlyInMachineTimeFromHoldToTheTarget) {
  const FeedOverrideRamp r(default_like());
  const double T = 75e-6;
  const Ramped up = run_ramp(r, T, 0.0, 1.5, 20000);
  bool reached = false;
  for (std::size_t i = 0; i < up.k.size(); ++i) {
    const double linear = r.rate_per_s() * up.t_start_s[i];  // K(t) = ρ·t from 0
    if (linear < 1.5) {
      ASSERT_NEAR(up.k[i], linear, 1e-9) << "period " << i;
    } else {
      ASSERT_EQ(up.k[i], 1.5) << "period " << i;  // on the target, never past it
      reached = true;
    }
  }
  EXPECT_TRUE(reached);
  // 0 → 150 % takes 1.5/ρ = 0.3 s of machine time
  std::size_t first = 0;
  while (up.k[first] < 1.5) ++first;
  EXPECT_NEAR(up.t_start_s[first], 1.5 / r.rate_per_s(), 2 * T);
  // the first moving period runs at K_min (within one hold step of it)
  std::size_t moving = 0;
  while (r.holds(up.k[moving])) ++moving;
  EXPECT_GE(up.k[moving], r.k_min());
  EXPECT_LT(up.k[moving], r.k_min() + r.rate_per_s() * T);
}

TEST(FeedOverrideRamp, FallsLinearlyToKMinThenHolds) {
  const FeedOverrideRamp r(default_like());
  const double T = 75e-6;
  const Ramped down = run_ramp(r, T, 1.0, 0.0, 20000);
  std::size_t i = 1;
  // linear while moving: K(t) = 1 − ρ·t, each step ρ·(T/K) exactly
  for (; i < down.k.size() && !r.holds(down.k[i]) && down.k[i] > r.k_min(); ++i)
    ASSERT_NEAR(down.k[i], 1.0 - r.rate_per_s() * down.t_start_s[i], 1e-9) << "period " << i;
  // the last moving period is at exactly K_min, then the machine holds
  ASSERT_LT(i, down.k.size());
  EXPECT_EQ(down.k[i], r.k_min());
  EXPECT_NEAR(down.t_start_s[i], (1.0 - r.k_min()) / r.rate_per_s(), T / r.k_min());
  for (++i; i < down.k.size(); ++i) ASSERT_TRUE(r.holds(down.k[i])) << "period " << i;
  EXPECT_EQ(down.k.back(), 0.0);
  // 100 % → hold in 0.2 s
  EXPECT_NEAR(1.0 / r.rate_per_s(), 0.2, 1e-12);
}

TEST(FeedOverrideRamp, NoStepIsLargerThanTheRateTimesThePeriod) {
  const FeedOverrideRamp r(default_like());
  const double T = 75e-6;
  const double targets[] = {1.5, 0.0, 0.7, 0.02, 1.2, 0.0, 1.0};
  double k = 1.0;
  for (double target : targets) {
    for (int n = 0; n < 8000; ++n) {
      const double len = r.holds(k) ? T : T / k;
      const double next = r.step(k, target, len);
      ASSERT_LE(std::abs(next - k), r.rate_per_s() * len * (1 + 1e-12));
      // toward the target, never past it (K_min is on the way to 0)
      ASSERT_LE(std::abs(next - target), std::abs(k - target) + 1e-15);
      k = next;
    }
    EXPECT_EQ(k, target);
  }
}

// Eq. (2) of the header, executed. One axis follows a plan at the limits the
// planner uses (rest → accelerate at amax/K_max² to vmax/K_max → cruise →
// brake to rest) while the override ramps; each period executes T of the
// plan in T/K. The acceleration, differenced period by period in machine
// time, stays within amax when the ramp and the plan's acceleration add up
// at K ≤ 1.2 (< K_max·sqrt(1 − s) = 122 %), and a ramp alone uses ρ·v ≈ s·amax.
struct Plan {
  double v_p, a_p, t_acc, t_cruise;
  [[nodiscard]] double end() const { return 2 * t_acc + t_cruise; }
  [[nodiscard]] double x(double tau) const {
    const double x_acc = 0.5 * a_p * t_acc * t_acc;
    if (tau <= t_acc) return 0.5 * a_p * tau * tau;
    if (tau <= t_acc + t_cruise) return x_acc + v_p * (tau - t_acc);
    const double tb = std::min(tau, end()) - t_acc - t_cruise;
    return x_acc + v_p * t_cruise + v_p * tb - 0.5 * a_p * tb * tb;
  }
};

// Peak |acceleration| executing `plan` from K = k0; at plan time tau_change
// the target becomes `target`.
double executed_peak_accel(const FeedOverrideRamp& r, double period_s, const Plan& plan, double k0,
                           double target, double tau_change) {
  double k = k0, tau = 0.0, x_prev = 0.0, v_prev = 0.0, len_prev = period_s, peak = 0.0;
  for (int n = 0; n < 4'000'000 && tau < plan.end(); ++n) {
    const bool held = r.holds(k);
    const double len = held ? period_s : period_s / k;
    if (!held) tau += period_s;  // one entry of the plan executed
    const double x = plan.x(tau);
    const double v = (x - x_prev) / len;
    peak = std::max(peak, std::abs(v - v_prev) / (0.5 * (len + len_prev)));
    x_prev = x;
    v_prev = v;
    len_prev = len;
    const double target_now = tau >= tau_change ? target : k0;
    if (target_now == 0.0 && k == 0.0) break;  // held for good
    k = r.step(k, target_now, len);
  }
  return peak;
}

TEST(FeedOverrideRamp, RampPlusPlanStaysWithinTheAxisAcceleration) {
  const MachineConfig m = default_like();
  const FeedOverrideRamp r(m);
  const double T = m.period_s();
  const double vmax = 500, amax = 5000, kmax = m.max_feed_override;
  const Plan plan{vmax / kmax, amax / (kmax * kmax), (vmax / kmax) / (amax / (kmax * kmax)), 0.3};
  ASSERT_NEAR(plan.t_acc, 0.15, 1e-12);
  const double brake = plan.t_acc + plan.t_cruise;
  // the ramp up while the plan speeds up: both terms add toward K = 1.2
  const double up = executed_peak_accel(r, T, plan, 0.0, 1.2, 0.0);
  EXPECT_LE(up, amax);
  EXPECT_GT(up, 0.85 * amax);
  // a feed hold from 120 % just as the plan brakes at its speed limit
  const double hold = executed_peak_accel(r, T, plan, 1.2, 0.0, brake);
  EXPECT_LE(hold, amax);
  EXPECT_GT(hold, 0.95 * amax);
  // a feed hold from 100 % while cruising: the ramp alone, ρ·vmax/K_max = amax/3
  // (the step into the hold, differenced over half a long period, 2/3)
  const double cruise = executed_peak_accel(r, T, plan, 1.0, 0.0, plan.t_acc + 0.1);
  EXPECT_LE(cruise, amax * 2.0 / 3.0 * 1.05);
  // ramp down while the plan speeds up: the terms oppose
  EXPECT_LE(executed_peak_accel(r, T, plan, 1.2, 0.0, 0.0), amax);
}

}  // namespace
}  // namespace lcnc::rt

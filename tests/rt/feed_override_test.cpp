#include "rt/feed_override.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "plan/ramp_room.h"

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
  // ρ_max = s·min(amax/vmax) = 1/2 · 10 /s
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
Ramped run_ramp(const FeedOverrideRamp& r, double period_s, double k0, double target, std::size_t periods) {
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
  const Ramped up = run_ramp(r, T, 0.0, 1.0, 20000);
  bool reached = false;
  for (std::size_t i = 0; i < up.k.size(); ++i) {
    const double linear = r.rate_per_s() * up.t_start_s[i];  // K(t) = ρ·t from 0
    if (linear < 1.0) {
      ASSERT_NEAR(up.k[i], linear, 1e-9) << "period " << i;
    } else {
      ASSERT_EQ(up.k[i], 1.0) << "period " << i;  // on the target, never past it
      reached = true;
    }
  }
  EXPECT_TRUE(reached);
  // 0 → 100 % takes 1/ρ = 0.2 s of machine time
  std::size_t first = 0;
  while (up.k[first] < 1.0) ++first;
  EXPECT_NEAR(up.t_start_s[first], 1.0 / r.rate_per_s(), 2 * T);
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
  const double targets[] = {1.0, 0.0, 0.7, 0.02, 0.9, 0.0, 1.0};
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

// Eq. (1) of the header, executed. One axis follows a plan at the machine's
// full limits (rest → accelerate at amax to vmax → cruise → brake at amax
// to rest), sampled once per period as the planner does, each entry with its
// ramp room (plan/ramp_room.h) as the planner computes it; the override
// ramps while each period executes T of the plan in T/K. The acceleration,
// differenced period by period in machine time, stays within amax however
// the ramp and the plan's own acceleration meet.
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

struct Executed {
  double peak_accel = 0.0;    // the largest axis acceleration
  double peak_after = 0.0;    // from the change of target on
  bool held = false;          // came to a hold (K = 0) for good
  double hold_at_tau = 0.0;   // the plan time it held at
  double hold_after_s = 0.0;  // machine time from the change of target to the hold
};

// Executes the planned poses `at(τ)` (X and Y) for τ in [0, end] from K = k0
// (a period scale, ≤ 1); from plan time tau_change on the target is `target`.
template <class PoseAt>
Executed execute(const MachineConfig& m, PoseAt at, double end, double k0, double target, double tau_change) {
  const FeedOverrideRamp r(m);
  const double T = m.period_s();
  // the planner's entries: poses at n·T and each one's room
  std::vector<Pose> x{at(0.0)};
  std::vector<RampRoom> room{RampRoom{}};
  RampRoomMeter meter(m, x[0]);
  for (std::size_t n = 1; static_cast<double>(n - 1) * T < end; ++n) {
    x.push_back(at(static_cast<double>(n) * T));
    room.push_back(meter.next(x.back()));
  }
  Executed out;
  double k = k0, len_prev = T, since_change = 0.0;
  // the motion before τ = 0 went on as planned
  Pose x_prev = x[0], v_prev = k0 * (x[1] - x[0]) / T;
  std::size_t next = 1;  // the next entry to execute
  for (int n = 0; n < 4'000'000 && next < x.size(); ++n) {
    const bool held = r.holds(k);
    const double len = held ? T : T / k;
    const Pose xn = held ? x_prev : x[next++];
    const Pose v = (xn - x_prev) / len;
    const double a = (v - v_prev).head<2>().cwiseAbs().maxCoeff() / (0.5 * (len + len_prev));
    out.peak_accel = std::max(out.peak_accel, a);
    const double tau = static_cast<double>(next - 1) * T;
    if (tau > tau_change) {
      out.peak_after = std::max(out.peak_after, a);
      since_change += len;
    }
    x_prev = xn;
    v_prev = v;
    len_prev = len;
    const double target_now = tau >= tau_change ? target : k0;
    if (target_now == 0.0 && k == 0.0) {  // held for good
      out.held = true;
      out.hold_at_tau = tau;
      out.hold_after_s = since_change;
      break;
    }
    k = r.step(k, target_now, len, next < room.size() ? room[next] : RampRoom{});
  }
  return out;
}

Executed execute(const MachineConfig& m, const Plan& plan, double k0, double target, double tau_change) {
  const auto at = [&plan](double tau) {
    Pose p = Pose::Zero();
    p[0] = plan.x(tau);
    return p;
  };
  return execute(m, at, plan.end(), k0, target, tau_change);
}

TEST(FeedOverrideRamp, RampPlusFullLimitPlanStaysWithinTheAxisAcceleration) {
  const MachineConfig m = default_like();
  const double vmax = 500, amax = 5000;
  const Plan plan{vmax, amax, vmax / amax, 0.3};
  const double brake = plan.t_acc + plan.t_cruise;
  // a resume from hold while the plan speeds up at full acceleration: the
  // ramp waits for room, and still gets to 100 %
  const Executed up = execute(m, plan, 0.0, 1.0, 0.0);
  EXPECT_LE(up.peak_accel, amax * (1 + 1e-6));
  // a feed hold from 100 % just as the plan brakes at its full deceleration:
  // K waits while the plan brakes, then falls; the machine holds before the
  // plan's own stop
  const Executed hold = execute(m, plan, 1.0, 0.0, brake);
  EXPECT_LE(hold.peak_accel, amax * (1 + 1e-6));
  // a feed hold half-way through the braking, from 60 %: room is (1 − K²)·amax
  const Executed half = execute(m, plan, 0.6, 0.0, brake + 0.5 * plan.t_acc);
  EXPECT_LE(half.peak_accel, amax * (1 + 1e-6));
  EXPECT_TRUE(half.held);
  // a feed hold while cruising: the ramp alone, ρ_max·vmax = amax/2 (the
  // step into the hold, differenced over half a long period, twice that),
  // and the machine holds within 0.2 s of machine time, 0.1 s of the plan's
  const Executed cruise = execute(m, plan, 1.0, 0.0, plan.t_acc + 0.05);
  EXPECT_LE(cruise.peak_accel, amax * (1 + 1e-6));
  EXPECT_GT(cruise.peak_after, amax * 0.45);
  ASSERT_TRUE(cruise.held);
  EXPECT_LT(cruise.hold_at_tau, plan.t_acc + 0.05 + 0.1 + 1e-3);
  // ramp down while the plan speeds up: the terms oppose
  EXPECT_LE(execute(m, plan, 1.0, 0.0, 0.5 * plan.t_acc).peak_accel, amax * (1 + 1e-6));
}

// The same without the room (an entry built by hand): a hold at full
// braking would take the axis past its limit — what the room is for.
TEST(FeedOverrideRamp, WithoutTheRoomAHoldAtFullBrakingWouldBreakTheLimit) {
  const MachineConfig m = default_like();
  const FeedOverrideRamp r(m);
  const double T = m.period_s(), vmax = 500, amax = 5000;
  const Plan plan{vmax, amax, vmax / amax, 0.3};
  double k = 1.0, tau = plan.t_acc + plan.t_cruise, x_prev = plan.x(tau), v_prev = vmax, peak = 0;
  while (tau < plan.end() && !r.holds(k)) {
    const double len = T / k;
    tau += T;
    const double v = (plan.x(tau) - x_prev) / len;
    peak = std::max(peak, std::abs(v - v_prev) / len);
    x_prev = plan.x(tau);
    v_prev = v;
    k = r.step(k, 0.0, len);
  }
  EXPECT_GT(peak, 1.3 * amax);
}

// A resume from a hold where one axis cruises fast and another just starts
// to move at its full acceleration (its speed tiny): K rises. (A room of
// r0 − K²·max |a|/|v| mixed the two axes: the starting axis's huge |a|/|v|
// left no room at any K, and the machine stayed held for good.)
TEST(FeedOverrideRamp, AResumeRisesWhenAnAxisStartsToMoveAtFullAcceleration) {
  MachineConfig m = default_like();
  const FeedOverrideRamp r(m);
  const double T = m.period_s();
  RampRoomMeter meter(m, Pose::Zero());
  Pose p = Pose::Zero();
  RampRoom room;
  for (int k = 1; k <= 3; ++k) {
    p[0] = 500.0 * T * k;                                        // X at 500 mm/s
    p[1] = 0.5 * 5000.0 * (k - 2) * (k - 2) * T * T * (k >= 2);  // Y starts at 5000 mm/s²
    room = meter.next(p);
  }
  double k = 0.0;
  for (int n = 0; n < 2000; ++n) k = r.step(k, 1.0, r.holds(k) ? T : T / k, room);
  EXPECT_GT(k, 0.1);
}

// A feed hold on a circle run at its centripetal limit at the axes' top
// speed: the axis that nears its reversal brakes at its full acceleration,
// the other cruises at 500 mm/s, so the room, not the ramp, sets the pace
// near each reversal. Begun anywhere on the circle, the hold comes within
// 0.21 s of machine time (the ramp alone: 0.20 s; 0.22 s with the room's
// rate taken from one axis and its share from another), and no axis leaves
// its limit.
TEST(FeedOverrideRamp, AHoldOnACircleAtItsCentripetalLimitComesInItsTime) {
  const MachineConfig m = default_like();
  const double amax = 5000, radius = 50, v = std::sqrt(amax * radius), w = v / radius;
  const double lap = 2 * std::numbers::pi / w;
  const auto at = [&](double tau) {
    Pose p = Pose::Zero();
    p[0] = radius * std::cos(w * tau);
    p[1] = radius * std::sin(w * tau);
    return p;
  };
  for (int eighth = 0; eighth < 8; ++eighth) {
    SCOPED_TRACE(eighth);
    const Executed hold = execute(m, at, 3 * lap, 1.0, 0.0, lap + eighth * lap / 8);
    ASSERT_TRUE(hold.held);
    EXPECT_LT(hold.hold_after_s, 0.21);
    EXPECT_LE(hold.peak_accel, amax * (1 + 1e-3));
  }
}

TEST(FeedOverrideRamp, PeriodScaleIsTheOverrideOverWhatTheEntryIsPlannedAt) {
  const FeedOverrideRamp r(default_like());
  EXPECT_EQ(r.period_scale(1.0, 1.0f), 1.0);
  EXPECT_EQ(r.period_scale(1.5, 1.0f), 1.0);  // never faster than planned
  EXPECT_DOUBLE_EQ(r.period_scale(1.2, 1.5f), 0.8);
  EXPECT_DOUBLE_EQ(r.period_scale(0.4, 1.5f), 0.4 / 1.5);
  EXPECT_EQ(r.period_scale(0.0, 1.5f), 0.0);  // a hold
  // a small override over a large plan still moves: K_min, not a hold
  EXPECT_EQ(r.period_scale(r.k_min(), 1.5f), r.k_min());
}

}  // namespace
}  // namespace lcnc::rt

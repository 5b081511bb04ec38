#include "plan/planner.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <random>
#include <vector>

#include "core/plan/random_moves.h"
#include "core/plan/test_machine.h"
#include "path/deviation_meter.h"
#include "support/test_scale.h"

namespace lcnc {
namespace {

// The facade chains every stage: G64 corners come out blended, G61 ones
// stopped, and every planned segment is observable.
// A planner reading `segs` in order.
Planner planner_over(const MachineConfig& m, const std::vector<Segment>& segs, std::size_t& i) {
  return Planner(m, [&segs, &i](Segment& out) {
    if (i == segs.size()) return SourceStatus::End;
    out = segs[i++];
    return SourceStatus::Item;
  });
}

// A blended line at 100 mm/s from `at` along +X by `dx`; `at` moves to its end.
Segment blended_x_line(Pose& at, double dx) {
  Segment s;
  s.kind = MotionKind::Linear;
  s.feed_mm_s = 100.0;
  s.path_mode = PathMode::Blend;
  s.blend_tolerance_mm = 0.01;
  s.start = at;
  at[0] += dx;
  s.end = at;
  return s;
}

TEST(Planner, ChainsMergerBlenderLookaheadAndInterpolator) {
  const auto m = testing::test_machine(100.0, 2000.0);
  std::vector<Segment> segs(2);
  for (int k = 0; k < 2; ++k) {
    segs[k].kind = MotionKind::Linear;
    segs[k].feed_mm_s = 50.0;
    segs[k].path_mode = PathMode::Blend;
    segs[k].blend_tolerance_mm = 0.01;
  }
  segs[0].start << 10, 10, 5, 0, 0, 0;
  segs[0].end << 20, 10, 5, 0, 0, 0;
  segs[1].start = segs[0].end;
  segs[1].end << 20, 20, 5, 0, 0, 0;
  std::size_t i = 0;
  Planner planner(m, [&](Segment& out) {
    if (i == segs.size()) return SourceStatus::End;
    out = segs[i++];
    return SourceStatus::Item;
  });
  std::vector<MotionKind> kinds;
  planner.on_planned([&](const PlannedSegment& p) { kinds.push_back(p.seg.kind); });
  PeriodSample s;
  PeriodSample last;
  while (planner.next(s) == SourceStatus::Item) last = s;
  EXPECT_TRUE(last.end_of_program);
  EXPECT_EQ(last.pose, segs[1].end);
  ASSERT_EQ(kinds.size(), 3u);  // line, blend arc, line
  EXPECT_EQ(kinds[1], MotionKind::Arc);
  EXPECT_EQ(planner.periods(), static_cast<std::uint64_t>(std::llround(last.t_s / m.period_s())));
}

}  // namespace
}  // namespace lcnc

// --- jerk limit (machine.max_jerk, plan/jerk_filter.h) -----------------------

namespace lcnc {
namespace {

Pose xyzc(double x, double y, double z, double c = 0.0) {
  Pose p = Pose::Zero();
  p << x, y, z, 0, 0, c;
  return p;
}

Segment cut(const Pose& a, const Pose& b, double feed, double tol, PathMode mode = PathMode::Blend) {
  Segment s;
  s.kind = MotionKind::Linear;
  s.start = a;
  s.end = b;
  s.feed_mm_s = feed;
  s.path_mode = mode;
  s.blend_tolerance_mm = mode == PathMode::Blend ? tol : 0.0;
  s.laser = LaserMode::Constant;
  s.power_pct = 50.0;
  return s;
}

// Peaks of one run, measured two ways:
//   * on the commanded poses, one period apart (v, a, j by first, second and
//     third differences over T);
//   * on the executed, step-quantized positions: the third difference over a
//     stride of h periods, Δ³_h/(h·T)³. Each position is within half a step q
//     of its pose, so the quantization adds at most (1+3+3+1)·q/2 = 4q to a
//     third difference: the allowance is 4q/(h·T)³. The stride-h difference
//     is a weighted mean of the period ones, so it never exceeds their peak.
// and the deviation of the executed positions from the programmed path.
struct JerkRun {
  std::array<double, kAxisCount> v{}, a{}, j{}, j_steps{};
  double max_dev = 0.0;
  double time_s = 0.0;
  std::vector<PeriodSample> samples;  // when asked for
  std::array<std::int64_t, kAxisCount> executed{}, commanded{};
  bool ended = false;
};

constexpr int kStride = 80;  // h, periods

JerkRun run_jerk(const MachineConfig& m, const std::vector<Segment>& segs, bool keep = false) {
  std::size_t i = 0, k = 0;
  Planner planner(m, testing::from(segs, i));
  DeviationMeter dm(testing::from(segs, k));
  const Pose start = segs.front().start;
  StepQuantizer q(m, start);
  JerkRun r;
  for (int ax = 0; ax < kAxisCount; ++ax) r.executed[ax] = q.commanded(ax);
  const double T = m.period_s();
  // the machine stands at the start before the first period
  std::vector<Pose> poses(3, start);
  std::vector<std::array<std::int64_t, kAxisCount>> steps(3 * kStride, r.executed);
  PeriodSample s;
  while (planner.next(s) == SourceStatus::Item) {
    if (keep) r.samples.push_back(s);
    const PeriodIncrement inc = q.quantize(s);
    for (int ax = 0; ax < kAxisCount; ++ax) r.executed[ax] += inc.steps[ax];
    poses.push_back(s.pose);
    steps.push_back(r.executed);
    const std::size_t n = poses.size(), ns = steps.size();
    for (int ax = 0; ax < kAxisCount; ++ax) {
      const double x0 = poses[n - 1][ax], x1 = poses[n - 2][ax], x2 = poses[n - 3][ax];
      r.v[ax] = std::max(r.v[ax], std::abs(x0 - x1) / T);
      r.a[ax] = std::max(r.a[ax], std::abs(x0 - 2 * x1 + x2) / (T * T));
      if (n >= 4) {
        const double x3 = poses[n - 4][ax];
        r.j[ax] = std::max(r.j[ax], std::abs(x0 - 3 * x1 + 3 * x2 - x3) / (T * T * T));
      }
      const double h = kStride * T;
      const auto& s0 = steps[ns - 1];
      const auto& s1 = steps[ns - 1 - kStride];
      const auto& s2 = steps[ns - 1 - 2 * kStride];
      const auto& s3 = steps[ns - 1 - 3 * kStride];
      const double d3 = static_cast<double>(s0[ax] - 3 * s1[ax] + 3 * s2[ax] - s3[ax]) / 1000.0;  // mm
      r.j_steps[ax] = std::max(r.j_steps[ax], std::abs(d3) / (h * h * h));
    }
    if (poses.size() > 8) poses.erase(poses.begin(), poses.begin() + 4);
    if (steps.size() > 6 * kStride) steps.erase(steps.begin(), steps.begin() + 3 * kStride);
    Vec3 exec;
    for (int ax = 0; ax < 3; ++ax) exec[ax] = static_cast<double>(r.executed[ax]) / 1000.0;
    r.max_dev = std::max(r.max_dev, dm.add(exec, s.segment));
    r.time_s = s.t_s;
    r.ended = s.end_of_program;
  }
  EXPECT_FALSE(q.owed());
  for (int ax = 0; ax < kAxisCount; ++ax) r.commanded[ax] = q.commanded(ax);
  return r;
}

// The quantization allowance of JerkRun::j_steps (q = 1 µm).
double steps_allowance(const MachineConfig& m) {
  const double h = kStride * m.period_s();
  return 4.0 * 0.001 / (h * h * h);
}

// Random polylines (fixed seed; LCNC_TEST_SCALE scales the count), blended at
// P, C turning along; J at which the acceleration must be lowered, and one at
// which it need not; on machines whose operator may set 100 % or 150 % (no
// difference: the plan is at the limits, the RT only slows it).
TEST(Planner, JerkLimitKeepsJerkAccelerationVelocityAndTolerance) {
  std::mt19937_64 rng(2024);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const int programs = testing::scaled(8);
  for (int p = 0; p < programs; ++p) {
    auto m = testing::test_machine(150.0, 3000.0);
    m.max_jerk = p % 2 == 0 ? 1e5 : 2e6;
    m.max_feed_override = p % 4 < 2 ? 1.0 : 1.5;
    const JerkLimit lim = jerk_limit(m);
    ASSERT_TRUE(lim.enabled());
    std::vector<Segment> segs;
    Pose at = xyzc(100 + 50 * u(rng), 100 + 50 * u(rng), 50);
    const double tol = 0.01 + 0.04 * u(rng);
    const double scale = p % 3 == 0 ? 0.2 : (p % 3 == 1 ? 1.0 : 8.0);
    for (int k = 0; k < 60; ++k) {
      Pose to = at + xyzc(scale * (u(rng) - 0.5), scale * (u(rng) - 0.5), 0.1 * scale * (u(rng) - 0.5));
      to[5] = at[5] + 2.0 * u(rng);
      segs.push_back(cut(at, to, 20 + 200 * u(rng), tol));
      at = to;
    }
    const JerkRun r = run_jerk(m, segs);
    EXPECT_TRUE(r.ended);
    EXPECT_LE(r.max_dev, tol) << "program " << p;
    for (int ax = 0; ax < kAxisCount; ++ax) {
      EXPECT_EQ(r.executed[ax], r.commanded[ax]);
      EXPECT_EQ(r.executed[ax], std::llround(at[ax] * 1000.0)) << "end pose, axis " << ax;
    }
    for (int ax = 0; ax < 3; ++ax) {
      // poses: exact up to rounding of the mean (~1e-13 mm: 1 mm/s³ here)
      const double jerk = m.max_jerk;
      EXPECT_LE(r.j[ax], jerk + 10.0) << "program " << p << " axis " << ax;
      EXPECT_LE(r.j_steps[ax], jerk + steps_allowance(m)) << "program " << p << " axis " << ax;
      EXPECT_LE(r.a[ax], lim.accel_scale * 3000.0 * (1 + 1e-6)) << "program " << p;
      EXPECT_LE(r.v[ax], 150.0 * (1 + 1e-9)) << "program " << p << " axis " << ax;
    }
    EXPECT_LE(r.a[5], 3600.0 * (1 + 1e-6));
  }
}

// The same check fails without the filter: the trapezoid's acceleration
// steps (3000 mm/s² in one period) are far beyond J = 100 m/s³ on the
// quantized trace, allowance included (~0.75·Δa/(h·T) ≈ 3.8e5 mm/s³).
TEST(Planner, WithoutJerkLimitTheQuantizedJerkIsFarAboveJ) {
  const auto m = testing::test_machine(150.0, 3000.0);
  const std::vector<Segment> segs = {cut(xyzc(10, 10, 5), xyzc(60, 10, 5), 100.0, 0.01)};
  const JerkRun r = run_jerk(m, segs);
  EXPECT_GT(r.j_steps[0], 3 * (1e5 + steps_allowance(m)));
}

// Lines and arcs meeting in fillets, at J where the acceleration is lowered.
TEST(Planner, JerkLimitStaysWithinPOnArcsAndFillets) {
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const int programs = testing::scaled(4);
  auto m = testing::test_machine(150.0, 3000.0);
  m.max_jerk = 2e5;
  for (int p = 0; p < programs; ++p) {
    const double tol = 0.01 + 0.03 * u(rng);
    const std::vector<Segment> segs = testing::random_lines_and_arcs(
        rng, xyzc(200, 200, 50), 60,
        [&](const Pose& a, const Pose& b, double feed) { return cut(a, b, feed, tol); });
    const JerkRun r = run_jerk(m, segs);
    EXPECT_LE(r.max_dev, tol) << "program " << p;
    EXPECT_GT(r.max_dev, 0.5 * tol) << "program " << p;  // the corners are still blended
    for (int ax = 0; ax < 3; ++ax) {
      EXPECT_EQ(r.executed[ax], r.commanded[ax]);
      EXPECT_LE(r.j[ax], m.max_jerk + 10.0) << "program " << p << " axis " << ax;
      EXPECT_LE(r.j_steps[ax], m.max_jerk + steps_allowance(m)) << "program " << p;
    }
  }
}

// G61: every corner is reached exactly (the commanded pose passes through it
// and the executed steps equal it), with a dwell and a rapid in between;
// outputs the RT kernel runs at the nominal period (Dwell) never move.
TEST(Planner, JerkLimitReachesExactStopsExactly) {
  auto m = testing::test_machine(150.0, 3000.0);
  m.max_jerk = 1e5;
  const Pose c[5] = {xyzc(10, 10, 5), xyzc(40.0001, 10, 5), xyzc(40.0001, 33.3333, 5), xyzc(10, 33.3333, 5),
                     xyzc(10, 10, 5)};
  std::vector<Segment> segs;
  for (int k = 0; k < 4; ++k) segs.push_back(cut(c[k], c[k + 1], 100.0, 0.0, PathMode::ExactPath));
  Segment dwell = segs.back();
  dwell.kind = MotionKind::Dwell;
  dwell.start = dwell.end = c[4];
  dwell.dwell_s = 0.05;
  segs.push_back(dwell);
  Segment rapid = cut(c[4], xyzc(70, 70, 20), 0.0, 0.0, PathMode::ExactPath);
  rapid.kind = MotionKind::Rapid;
  segs.push_back(rapid);
  const JerkRun r = run_jerk(m, segs, true);
  for (int k = 1; k < 5; ++k) {
    bool reached = false;
    for (const PeriodSample& s : r.samples) reached = reached || s.pose == c[k];
    EXPECT_TRUE(reached) << "corner " << k;
  }
  EXPECT_EQ(r.samples.back().pose, rapid.end);
  EXPECT_TRUE(r.samples.back().end_of_program);
  Pose prev = c[0];
  for (const PeriodSample& s : r.samples) {
    if (s.kind == MotionKind::Dwell) {
      EXPECT_EQ(s.pose, prev) << s.t_s;
    }
    prev = s.pose;
  }
  EXPECT_LE(r.max_dev, 0.0006);  // only the step rounding: lines stay lines
  for (int ax = 0; ax < 3; ++ax) EXPECT_LE(r.j_steps[ax], m.max_jerk + steps_allowance(m));
}

// Laser in step with the delayed motion: M3 lights only where the head is on
// a cut, the G4 fires exactly its own time standing, rapids stay dark; M4
// follows the filtered speed and is dark at rest.
TEST(Planner, JerkLimitKeepsTheLaserInStepWithMotion) {
  auto m = testing::test_machine(150.0, 3000.0);
  m.max_jerk = 1e5;
  const Pose a = xyzc(10, 10, 5), b = xyzc(50, 10, 5), c = xyzc(50, 40, 5), d = xyzc(90, 40, 5);
  Segment m3 = cut(a, b, 100.0, 0.0, PathMode::ExactPath);
  Segment pierce = m3;
  pierce.kind = MotionKind::Dwell;
  pierce.start = pierce.end = b;
  pierce.dwell_s = 0.03;
  Segment rapid = cut(b, c, 0.0, 0.0, PathMode::ExactPath);
  rapid.kind = MotionKind::Rapid;
  Segment m4 = cut(c, d, 80.0, 0.01);
  m4.laser = LaserMode::Dynamic;
  const JerkRun r = run_jerk(m, {m3, pierce, rapid, m4}, true);
  const double T = m.period_s();
  int lit_standing = 0;
  Pose prev = a;
  for (const PeriodSample& s : r.samples) {
    const Vec3 p = s.pose.head<3>();
    const double speed = (s.pose - prev).head<3>().norm() / T;
    const bool standing = s.pose == prev;
    if (s.kind == MotionKind::Rapid) {
      EXPECT_EQ(s.power_pct, 0.0f) << s.t_s;
    }
    if (s.power_cap_pct == 0.0f && s.power_pct > 0.0f) {  // M3: on the first cut
      EXPECT_LE(distance_to_segment(p, a.head<3>(), b.head<3>()), 1e-9) << s.t_s;
      if (standing) ++lit_standing;
    }
    if (s.power_cap_pct > 0.0f) {  // M4: S · speed / F, speed the filtered one
      EXPECT_LE(distance_to_segment(p, c.head<3>(), d.head<3>()), 1e-9) << s.t_s;
      if (standing) {
        EXPECT_EQ(s.power_pct, 0.0f) << s.t_s;
      }
      // the mean of speeds at period ends vs the mean over the period: ≤ a·T/2
      EXPECT_NEAR(s.power_pct, 50.0 * speed / 80.0, 50.0 * (3000.0 * T / 2) / 80.0 + 1e-4) << s.t_s;
    }
    prev = s.pose;
  }
  // the pierce's periods, plus at most the one or two periods the head
  // stands at each end of the cut with M3 on (the hold's turn)
  const int pierce_periods = static_cast<int>(std::lround(0.03 / T));
  EXPECT_GE(lit_standing, pierce_periods - 1);
  EXPECT_LE(lit_standing, pierce_periods + 1 + 2 * 2);
  EXPECT_EQ(r.samples.back().power_pct, 0.0f);
}

// Without the key every stage runs as before: the samples are those of the
// stages chained directly, bit for bit.
TEST(Planner, WithoutJerkLimitThePlanIsBitIdentical) {
  const auto m = testing::test_machine(150.0, 3000.0);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Segment> segs;
  Pose at = xyzc(100, 100, 50);
  for (int k = 0; k < 80; ++k) {
    const Pose to = at + xyzc(5 * (u(rng) - 0.5), 5 * (u(rng) - 0.5), 0.5 * (u(rng) - 0.5));
    segs.push_back(cut(at, to, 20 + 200 * u(rng), 0.01, k % 7 == 0 ? PathMode::ExactPath : PathMode::Blend));
    at = to;
  }
  std::size_t i = 0, j = 0;
  Planner planner(m, testing::from(segs, i));
  PathBlender blender(m, testing::from(segs, j));
  Lookahead la(m, [&](const IndexedSegment*& s) { return blender.next(s); });
  CoarseInterpolator ci(m, [&](const PlannedSegment*& p) { return la.next(p); });
  PeriodSample x, y;
  std::uint64_t n = 0;
  for (;;) {
    const SourceStatus sx = planner.next(x), sy = ci.next(y);
    ASSERT_EQ(sx, sy);
    if (sx != SourceStatus::Item) break;
    ASSERT_EQ(x.pose, y.pose) << n;
    ASSERT_EQ(x.t_s, y.t_s);
    ASSERT_EQ(x.speed, y.speed);
    ASSERT_EQ(x.power_pct, y.power_pct);
    ASSERT_EQ(x.segment, y.segment);
    ASSERT_EQ(x.kind, y.kind);
    ++n;
  }
  EXPECT_GT(n, 1000u);
  EXPECT_FALSE(planner.jerk_limit().enabled());
}

}  // namespace
}  // namespace lcnc

// --- feed override above 100 %: planned for (Planner::set_feed_scale) --------

namespace lcnc {
namespace {

// A line of 0.05 mm chords at F 100 mm/s. Raised to 150 % mid-way, the
// planner re-plans what it has not handed out: the speed rises to 150 mm/s
// without a jump (no period changes speed by more than the acceleration
// allows) and the samples say the override they are planned at. Lowered
// again, the segments already planned at 150 % keep their speed (the RT
// slows them), and the ones that come in later are planned at 100 %.
TEST(Planner, ARaisedOverrideIsPlannedForFromWhereThePlanStandsWithoutAJump) {
  const auto m = testing::test_machine(500.0, 5000.0);
  std::vector<Segment> segs;
  Pose at = Pose::Zero();
  at << 10, 10, 5, 0, 0, 0;
  for (int k = 0; k < 4000; ++k) segs.push_back(blended_x_line(at, 0.05));
  std::size_t i = 0;
  Planner planner = planner_over(m, segs, i);
  const double T = m.period_s();
  PeriodSample s;
  double prev_x = 10.0, prev_v = 0.0, worst_dv = 0.0;
  std::vector<double> speed;
  std::vector<float> k_plan;
  while (planner.next(s) == SourceStatus::Item) {
    const double v = (s.pose[0] - prev_x) / T;
    worst_dv = std::max(worst_dv, std::abs(v - prev_v));
    prev_x = s.pose[0];
    prev_v = v;
    speed.push_back(v);
    k_plan.push_back(s.k_plan);
    if (speed.size() == 4000) planner.set_feed_scale(1.5);
    if (speed.size() == 8000) planner.set_feed_scale(1.0);
  }
  EXPECT_LE(worst_dv, 5000.0 * T * (1 + 1e-6));  // (speeds from differenced poses)
  ASSERT_GT(speed.size(), 10'000u);
  EXPECT_NEAR(speed[3999], 100.0, 1e-6);
  EXPECT_EQ(k_plan[3999], 1.0f);
  // the window planned before the raise is handed out again at 150 %: the
  // speed rises at once (50 mm/s at 5000 mm/s² takes 134 periods)
  EXPECT_NEAR(speed[4200], 150.0, 1e-6);
  EXPECT_EQ(k_plan[4200], 1.5f);
  // lowered: what is planned keeps its speed (the window: 4 braking lengths
  // of 150 mm/s, 9 mm, 800 periods), what comes later is at 100 %
  EXPECT_NEAR(speed[8001], 150.0, 1e-6);
  EXPECT_EQ(k_plan[8001], 1.5f);
  EXPECT_NEAR(speed[9500], 100.0, 1e-6);
  EXPECT_EQ(k_plan[9500], 1.0f);
  EXPECT_LE(*std::max_element(speed.begin(), speed.end()), 150.0 + 1e-6);
}

// A dwell after segments planned at 150 % is planned at 100 %: its time is
// the program's (the RT runs dwells at the nominal period), and the moves
// around it keep theirs.
TEST(Planner, ADwellIsPlannedAtOneHundredPercentWhateverTheOverride) {
  const auto m = testing::test_machine(500.0, 5000.0);
  // more lines than the look-ahead's ring has slots (1024): the dwell takes
  // a slot a line planned at 150 % held before
  std::vector<Segment> segs;
  Pose at = Pose::Zero();
  at << 10, 10, 5, 0, 0, 0;
  for (int k = 0; k < 1100; ++k) segs.push_back(blended_x_line(at, 0.05));
  Segment dwell;
  dwell.kind = MotionKind::Dwell;
  dwell.dwell_s = 0.01;
  dwell.start = dwell.end = at;
  segs.push_back(dwell);
  std::size_t i = 0;
  Planner planner = planner_over(m, segs, i);
  planner.set_feed_scale(1.5);
  PeriodSample s;
  std::size_t dwelling = 0, fast = 0;
  while (planner.next(s) == SourceStatus::Item) {
    if (s.kind == MotionKind::Dwell) {
      ++dwelling;
      EXPECT_EQ(s.k_plan, 1.0f);
    } else if (s.kind == MotionKind::Linear && !s.end_of_program) {
      ++fast;
      EXPECT_EQ(s.k_plan, 1.5f);
    }
  }
  EXPECT_NEAR(static_cast<double>(dwelling), 0.01 / m.period_s(), 2.0);
  EXPECT_GT(fast, 500u);
}

// Moves under M50 P0 (the override off) are planned at 100 % however high
// the operator's override: their feed is the program's, and their samples
// say so (the RT runs them at K = 1); the moves around them take the
// override, and nothing merges across the switch.
TEST(Planner, MovesWithTheOverrideOffArePlannedAtTheProgramsFeed) {
  const auto m = testing::test_machine(500.0, 5000.0);
  std::vector<Segment> segs;
  Pose at = Pose::Zero();
  at << 10, 10, 5, 0, 0, 0;
  for (int k = 0; k < 600; ++k) {
    segs.push_back(blended_x_line(at, 0.05));
    if (k >= 200 && k < 400) segs.back().feed_control = kFeedOverrideOff;
  }
  std::size_t i = 0;
  Planner planner = planner_over(m, segs, i);
  planner.set_feed_scale(1.5);
  PeriodSample s;
  double prev_x = 10.0, top_off = 0.0, top_on = 0.0;
  std::size_t off = 0;
  while (planner.next(s) == SourceStatus::Item) {
    const double v = (s.pose[0] - prev_x) / m.period_s();
    prev_x = s.pose[0];
    if (s.end_of_program) continue;
    if ((s.feed_control & kFeedOverrideOff) != 0) {
      ++off;
      EXPECT_EQ(s.k_plan, 1.0f);
      top_off = std::max(top_off, v);
    } else {
      EXPECT_EQ(s.k_plan, 1.5f);
      top_on = std::max(top_on, v);
    }
  }
  EXPECT_GT(off, 1000u);              // 10 mm at 100 mm/s: 1333 periods
  EXPECT_NEAR(top_off, 100.0, 0.01);  // (differenced poses)
  EXPECT_NEAR(top_on, 150.0, 0.01);
}

}  // namespace
}  // namespace lcnc

#include "plan/lookahead.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "core/plan/random_moves.h"
#include "core/plan/test_machine.h"
#include "path/deviation_meter.h"
#include "plan/coarse_interpolator.h"
#include "plan/motion_stats.h"
#include "plan/path_blender.h"
#include "support/test_scale.h"

namespace lcnc {
namespace {

Segment g1(const Pose& a, const Pose& b, double feed, double tol) {
  Segment s;
  s.kind = MotionKind::Linear;
  s.start = a;
  s.end = b;
  s.feed_mm_s = feed;
  s.path_mode = PathMode::Blend;
  s.blend_tolerance_mm = tol;
  return s;
}

Pose xyz_lookahead(double x, double y, double z) {
  Pose p = Pose::Zero();
  p << x, y, z, 0, 0, 0;
  return p;
}

struct Outcome {
  double time_s = 0.0;
  double max_dev = 0.0;
  std::array<double, kAxisCount> peak_v{}, peak_a{};
  std::array<std::int64_t, kAxisCount> sum{}, commanded{};
  std::size_t max_window = 0;
  double max_entry_exit_gap = 0.0;  // |v_exit(i) − v_entry(i+1)|
};

// The whole planner pipeline: blender → look-ahead → coarse interpolation →
// step quantizer; deviation measured on the quantized positions against the
// program segments.
Outcome run_lookahead(const MachineConfig& m, const std::vector<Segment>& segs) {
  std::size_t i = 0, j = 0;
  PathBlender blender(m, testing::from(segs, i));
  Lookahead la(m, [&](const IndexedSegment*& s) { return blender.next(s); });
  double prev_exit = 0.0;
  Outcome o;
  CoarseInterpolator ci(m, [&](const PlannedSegment*& p) {
    const SourceStatus st = la.next(p);
    if (st == SourceStatus::Item) {
      o.max_entry_exit_gap = std::max(o.max_entry_exit_gap, std::abs(p->profile.v0 - prev_exit));
      prev_exit = p->profile.v1;
    }
    return st;
  });
  DeviationMeter dm(testing::from(segs, j));
  const Pose start = segs.front().start;
  StepQuantizer q(m, start);
  MotionStats st(m.period_s(), start);
  for (int a = 0; a < kAxisCount; ++a) o.sum[a] = q.commanded(a);
  PeriodSample s;
  while (ci.next(s) == SourceStatus::Item) {
    st.add(s.pose);
    const PeriodIncrement inc = q.quantize(s);
    for (int a = 0; a < kAxisCount; ++a) o.sum[a] += inc.steps[a];
    Vec3 exec;
    for (int a = 0; a < 3; ++a) exec[a] = static_cast<double>(o.sum[a]) / 1000.0;
    dm.add(exec, s.segment);
    o.time_s = s.t_s;
  }
  st.finish();
  EXPECT_FALSE(q.owed());
  for (int a = 0; a < kAxisCount; ++a) o.commanded[a] = q.commanded(a);
  o.max_dev = dm.max_mm();
  o.peak_v = st.peak_velocity();
  o.peak_a = st.peak_acceleration();
  o.max_window = la.max_window_seen();
  return o;
}

TEST(Lookahead, BlendedSquareIsFasterThanExactStopAndStaysInTolerance) {
  const auto m = testing::test_machine(100.0, 2000.0);
  std::vector<Segment> blend, stop;
  const double c[5][2] = {{10, 10}, {60, 10}, {60, 60}, {10, 60}, {10, 10}};
  for (int lap = 0; lap < 3; ++lap)
    for (int k = 0; k < 4; ++k) {
      blend.push_back(
          g1(xyz_lookahead(c[k][0], c[k][1], 5), xyz_lookahead(c[k + 1][0], c[k + 1][1], 5), 100, 0.01));
      Segment e = blend.back();
      e.path_mode = PathMode::ExactPath;
      stop.push_back(e);
    }
  const Outcome b = run_lookahead(m, blend), e = run_lookahead(m, stop);
  EXPECT_LT(b.time_s, e.time_s);  // 90° corners: blends at 6.5 mm/s, little to gain
  EXPECT_LE(b.max_dev, 0.01);
  EXPECT_GT(b.max_dev, 0.005);  // the corners really are cut
  EXPECT_LE(e.max_dev, 0.001);  // exact stop: only step rounding
  for (int a = 0; a < 3; ++a) {
    EXPECT_LE(b.peak_v[a], 100.0 * (1 + 1e-9));
    EXPECT_LE(b.peak_a[a], 2000.0 * (1 + 1e-6)) << a;
    EXPECT_EQ(b.sum[a], b.commanded[a]);
  }
  EXPECT_LE(b.max_entry_exit_gap, 1e-9);
}

TEST(Lookahead, ShallowCornersAreTakenAtSpeed) {
  const auto m = testing::test_machine(100.0, 2000.0);
  std::vector<Segment> blend, stop;
  for (int k = 0; k < 24; ++k) {  // a 12-gon twice: 30° corners
    auto pt = [](int j) {
      const double a = 2 * 3.14159265358979 * j / 12.0;
      return xyz_lookahead(100 + 30 * std::cos(a), 100 + 30 * std::sin(a), 5);
    };
    blend.push_back(g1(pt(k), pt(k + 1), 100, 0.05));
    stop.push_back(blend.back());
    stop.back().path_mode = PathMode::ExactPath;
  }
  const Outcome b = run_lookahead(m, blend), e = run_lookahead(m, stop);
  EXPECT_LT(b.time_s, 0.9 * e.time_s);  // corners at ~52 mm/s instead of a stop
  EXPECT_LE(b.max_dev, 0.05);
}

// 100 % is the time-optimal plan at the machine's full limits, whatever
// override the operator may set (machine.max_feed_override is no derate).
TEST(Lookahead, PlansAtTheMachinesFullLimits) {
  auto m = testing::test_machine(100.0, 2000.0);
  m.max_feed_override = 1.5;
  const Outcome o = run_lookahead(m, {g1(xyz_lookahead(0, 0, 0), xyz_lookahead(100, 0, 0), 1000.0, 0.01)});
  EXPECT_NEAR(o.peak_v[0], 100.0, 1e-6);
  EXPECT_LE(o.peak_a[0], 2000.0 * (1 + 1e-6));
  EXPECT_GT(o.peak_a[0], 2000.0 * 0.99);
}

// Random polylines (fixed seed; LCNC_TEST_SCALE scales the count): never
// beyond the axis limits, never beyond P, every step delivered, speeds
// continuous from segment to segment.
TEST(Lookahead, RandomPolylinesStayWithinLimitsAndTolerance) {
  const auto m = testing::test_machine(150.0, 3000.0);
  std::mt19937_64 rng(99);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const int programs = testing::scaled(12);
  for (int p = 0; p < programs; ++p) {
    std::vector<Segment> segs;
    Pose at = xyz_lookahead(100 + 50 * u(rng), 100 + 50 * u(rng), 50);
    const double tol = 0.002 + 0.05 * u(rng);
    const double scale = p % 3 == 0 ? 0.05 : (p % 3 == 1 ? 1.0 : 10.0);
    for (int k = 0; k < 200; ++k) {
      Pose to =
          at + xyz_lookahead(scale * (u(rng) - 0.5), scale * (u(rng) - 0.5), 0.1 * scale * (u(rng) - 0.5));
      to[5] = at[5] + 2.0 * u(rng);  // C turns along: blending stays on
      segs.push_back(g1(at, to, 20 + 200 * u(rng), tol));
      at = to;
    }
    const Outcome o = run_lookahead(m, segs);
    EXPECT_LE(o.max_dev, tol) << "program " << p;
    EXPECT_LE(o.max_entry_exit_gap, 1e-9);
    for (int a = 0; a < kAxisCount; ++a) {
      EXPECT_EQ(o.sum[a], o.commanded[a]);
      EXPECT_EQ(o.sum[a], std::llround(at[a] * 1000.0));
    }
    for (int a = 0; a < 3; ++a) {
      EXPECT_LE(o.peak_v[a], 150.0 * (1 + 1e-9)) << "program " << p << " axis " << a;
      EXPECT_LE(o.peak_a[a], 3000.0 * (1 + 1e-6)) << "program " << p << " axis " << a;
    }
    EXPECT_LE(o.peak_v[5], 360.0 * (1 + 1e-9));
    EXPECT_LE(o.peak_a[5], 3600.0 * (1 + 1e-6));
  }
}

// Lines and arcs meeting at corners (fillets): within P, within the limits,
// every step delivered.
TEST(Lookahead, RandomLinesAndArcsStayWithinLimitsAndTolerance) {
  const auto m = testing::test_machine(150.0, 3000.0);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const int programs = testing::scaled(8);
  for (int p = 0; p < programs; ++p) {
    const double tol = 0.005 + 0.03 * u(rng);
    const std::vector<Segment> segs = testing::random_lines_and_arcs(
        rng, xyz_lookahead(200, 200, 50), 120,
        [&](const Pose& a, const Pose& b, double feed) { return g1(a, b, feed, tol); });
    const Outcome o = run_lookahead(m, segs);
    EXPECT_LE(o.max_dev, tol) << "program " << p;
    EXPECT_GT(o.max_dev, 0.5 * tol) << "program " << p;  // the corners really are filleted
    EXPECT_LE(o.max_entry_exit_gap, 1e-9);
    for (int a = 0; a < 3; ++a) {
      EXPECT_EQ(o.sum[a], o.commanded[a]);
      EXPECT_LE(o.peak_v[a], 150.0 * (1 + 1e-9)) << "program " << p << " axis " << a;
      EXPECT_LE(o.peak_a[a], 3000.0 * (1 + 1e-6)) << "program " << p << " axis " << a;
    }
  }
}

TEST(Lookahead, NaiveCamMergingStaysWithinP) {
  const auto m = testing::test_machine(100.0, 2000.0);
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Segment> segs;
  Pose at = xyz_lookahead(50, 50, 5);
  for (int k = 0; k < 400; ++k) {  // wavy CAM chords: some runs merge, corners blend
    const Pose to = at + xyz_lookahead(0.3, 0.004 * u(rng) + (k % 40 < 20 ? 0.05 : -0.05), 0);
    Segment s = g1(at, to, 100.0, 0.02);
    s.naive_cam_tolerance_mm = 0.02;
    segs.push_back(s);
    at = to;
  }
  const Outcome o = run_lookahead(m, segs);
  EXPECT_LE(o.max_dev, 0.02);
  for (int a = 0; a < 3; ++a) EXPECT_EQ(o.sum[a], o.commanded[a]);
}

TEST(Lookahead, TinyChordCircleRunsAtItsCentripetalLimit) {
  const auto m = testing::test_machine(100.0, 2000.0);
  std::vector<Segment> segs;
  const double r = 2.0;    // v_max = sqrt(a·r) = 63 mm/s < F
  const int n = 1257 * 4;  // 0.01 mm chords, 4 laps
  auto pt = [&](int k) {
    const double a = 2 * 3.14159265358979 * (k % 1257) / 1257.0;
    return xyz_lookahead(100 + r * std::cos(a), 100 + r * std::sin(a), 5);
  };
  for (int k = 0; k < n; ++k) segs.push_back(g1(pt(k), pt(k + 1), 100.0, 0.01));
  const Outcome o = run_lookahead(m, segs);
  const double chord = (pt(0) - pt(1)).norm();
  const double length = n * chord;
  const double v_limit = std::sqrt(2000.0 * r);
  // several chords per period are consumed: no per-segment cap from the
  // period; the speed is the centripetal limit (within its 0.5 % share)
  EXPECT_LT(o.time_s, length / (0.99 * v_limit) + 2 * v_limit / 2000.0);
  EXPECT_GT(o.time_s, length / v_limit);
  EXPECT_LE(o.peak_a[0], 2000.0 * (1 + 1e-6));
  EXPECT_LE(o.max_dev, 0.01);
}

TEST(Lookahead, DenseChordCircleRunsAtFeedWithBoundedWindow) {
  const auto m = testing::test_machine(100.0, 2000.0);
  std::vector<Segment> segs;
  const int n = 20000;  // 0.0126 mm chords on a 40 mm radius, 5 laps
  const double r = 40.0;
  auto pt = [&](int k) {
    const double a = 2 * 3.14159265358979 * (k % 4000) / 4000.0;
    return xyz_lookahead(200 + r * std::cos(a), 200 + r * std::sin(a), 10);
  };
  for (int k = 0; k < n; ++k) segs.push_back(g1(pt(k), pt(k + 1), 100.0, 0.01));
  const Outcome o = run_lookahead(m, segs);
  const double length = n * (pt(0) - pt(1)).norm();
  // at F6000 = 100 mm/s the path is feed-limited: time ≈ L/v + accel/decel
  EXPECT_LT(o.time_s, length / 100.0 + 2 * 100.0 / 2000.0 + 0.01);
  EXPECT_LE(o.max_dev, 0.01);
  EXPECT_LT(o.max_window, 2000u);  // bounded by the braking distance, not the program
}

// The test machine with an A axis as the shipped machine's.
MachineConfig with_a_axis() {
  MachineConfig m = testing::test_machine(100.0, 2000.0);
  AxisConfig& ax = m.axis(Axis::A);
  ax.present = true;
  ax.axis = Axis::A;
  ax.min = -95.0;
  ax.max = 95.0;
  ax.max_velocity = 180.0;
  ax.max_acceleration = 1800.0;
  ax.steps_per_unit = 1000.0;
  return m;
}

// Every axis within its limits (per period, from the unquantized poses),
// every A step delivered, the path within P.
void expect_within_limits(const MachineConfig& m, const Outcome& o) {
  for (int a = 0; a < kAxisCount; ++a) {
    if (!m.axes[a].present) continue;
    EXPECT_LE(o.peak_v[a], m.axes[a].max_velocity * (1 + 1e-9)) << a;
    EXPECT_LE(o.peak_a[a], m.axes[a].max_acceleration * (1 + 1e-6)) << a;
    EXPECT_EQ(o.sum[a], o.commanded[a]) << a;
  }
  EXPECT_LE(o.max_dev, 0.01);
}

// A line that swings A, then a short line without A motion that its two
// blends use up entirely, then another: the short line is dropped, and the
// second blend (no A motion) follows the first (A moving at some deg/mm)
// directly. That join is no tangent one: A must not jump in speed there.
TEST(Lookahead, BlendAfterALineUsedUpKeepsTheRotaryRateOfTheOneBefore) {
  const MachineConfig m = with_a_axis();
  Pose swung = xyz_lookahead(11, 10, 5);
  swung[3] = 10.0;  // 10° of A over 1 mm of X
  Pose corner = xyz_lookahead(11, 10.001, 5);
  corner[3] = 10.0;
  Pose end = xyz_lookahead(12, 10.001, 5);
  end[3] = 10.0;
  const std::vector<Segment> segs = {g1(xyz_lookahead(10, 10, 5), swung, 50.0, 0.01),
                                     g1(swung, corner, 50.0, 0.01), g1(corner, end, 50.0, 0.01)};
  expect_within_limits(m, run_lookahead(m, segs));
}

// The other way round: the short line used up by its blends is the one that
// swings A (1° over 1 µm), its neighbours do not. Both blends carry part of
// its swing, at different rates, and the line after the second has none:
// neither join is tangent.
TEST(Lookahead, BlendsOfALineUsedUpThatSwingsARotaryAxisAreNoTangentJoins) {
  const MachineConfig m = with_a_axis();
  Pose corner = xyz_lookahead(11, 10, 5), swung = xyz_lookahead(11, 10.001, 5),
       end = xyz_lookahead(12, 10.001, 5);
  swung[3] = end[3] = 1.0;
  const std::vector<Segment> segs = {g1(xyz_lookahead(10, 10, 5), corner, 50.0, 0.01),
                                     g1(corner, swung, 50.0, 0.01), g1(swung, end, 50.0, 0.01)};
  expect_within_limits(m, run_lookahead(m, segs));
}

}  // namespace
}  // namespace lcnc

#include "plan/coarse_interpolator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "core/plan/test_machine.h"
#include "plan/lookahead.h"
#include "plan/motion_stats.h"
#include "plan/path_blender.h"

namespace lcnc {
namespace {

Segment line_coarse_interpolator(const Pose& a, const Pose& b, double feed, std::uint32_t line_no = 1) {
  Segment s;
  s.kind = MotionKind::Linear;
  s.start = a;
  s.end = b;
  s.feed_mm_s = feed;
  s.line = line_no;
  return s;
}

Pose xyz(double x, double y, double z) {
  Pose p = Pose::Zero();
  p << x, y, z, 0, 0, 0;
  return p;
}

// Runs segments through exact-stop planning, coarse interpolation and the
// quantizer; returns the samples and the summed increments.
struct PipelineRun {
  std::vector<PeriodSample> samples;
  std::array<std::int64_t, kAxisCount> sum{};
  std::array<std::int64_t, kAxisCount> commanded{};
  std::int32_t max_abs_inc = 0;
  std::uint64_t entries = 0;
  bool end_flag_last = false;
};

PipelineRun run(const MachineConfig& m, const std::vector<Segment>& segs, const Pose& start) {
  std::size_t i = 0;
  PathBlender blender(m, [&](Segment& out) {
    if (i == segs.size()) return SourceStatus::End;
    out = segs[i++];
    return SourceStatus::Item;
  });
  Lookahead planner(m, [&](const IndexedSegment*& s) { return blender.next(s); });
  CoarseInterpolator ci(m, [&](const PlannedSegment*& p) { return planner.next(p); });
  StepQuantizer q(m, start);
  PipelineRun r;
  for (int a = 0; a < kAxisCount; ++a) r.sum[a] = q.commanded(a);
  PeriodSample s;
  auto take = [&](const PeriodIncrement& inc) {
    for (int a = 0; a < kAxisCount; ++a) {
      r.sum[a] += inc.steps[a];
      r.max_abs_inc = std::max(r.max_abs_inc, std::abs(inc.steps[a]));
    }
    ++r.entries;
    r.end_flag_last = inc.end_of_program;
  };
  while (ci.next(s) == SourceStatus::Item) {
    r.samples.push_back(s);
    take(q.quantize(s));
  }
  while (q.owed()) take(q.pay_owed(r.samples.back()));
  for (int a = 0; a < kAxisCount; ++a) r.commanded[a] = q.commanded(a);
  return r;
}

TEST(CoarseInterpolator, LastSampleIsExactlyTheEndPose) {
  const auto m = testing::test_machine();
  const PipelineRun r =
      run(m, {line_coarse_interpolator(xyz(1, 1, 1), xyz(101.2345, 51.0001, 1), 100.0)}, xyz(1, 1, 1));
  ASSERT_FALSE(r.samples.empty());
  EXPECT_TRUE(r.samples.back().end_of_program);
  EXPECT_EQ(r.samples.back().pose, xyz(101.2345, 51.0001, 1));
  EXPECT_EQ(r.sum[0], 101235);  // round(101.2345 mm · 1000)
  EXPECT_EQ(r.sum[1], 51000);
  EXPECT_TRUE(r.end_flag_last);
}

// A source that fails after two good lines (the file changed since it was
// checked): the motion before the failure ends at rest, exactly at the
// second line's end and with end_of_program, and only then comes the Error.
TEST(CoarseInterpolator, SourceErrorEndsAtRestWhereTheLastGoodSegmentEnds) {
  const auto m = testing::test_machine();
  const std::vector<Segment> segs = {line_coarse_interpolator(xyz(0, 0, 0), xyz(50, 0, 0), 100.0, 1),
                                     line_coarse_interpolator(xyz(50, 0, 0), xyz(50, 30, 0), 100.0, 2)};
  std::size_t i = 0;
  PathBlender blender(m, [&](Segment& out) {
    if (i == segs.size()) return SourceStatus::Error;
    out = segs[i++];
    return SourceStatus::Item;
  });
  Lookahead planner(m, [&](const IndexedSegment*& s) { return blender.next(s); });
  CoarseInterpolator ci(m, [&](const PlannedSegment*& p) { return planner.next(p); });
  std::vector<PeriodSample> samples;
  PeriodSample s;
  SourceStatus st;
  while ((st = ci.next(s)) == SourceStatus::Item) samples.push_back(s);
  EXPECT_EQ(st, SourceStatus::Error);
  EXPECT_EQ(ci.next(s), SourceStatus::Error);  // and stays so
  ASSERT_GE(samples.size(), 2u);
  EXPECT_TRUE(samples.back().end_of_program);
  EXPECT_EQ(samples.back().pose, xyz(50, 30, 0));
  EXPECT_EQ(samples.back().line, 2u);
  // at rest: the last period moved less than one period's travel at 2 % of
  // the feed (the profile decelerates into the end)
  const PeriodSample& a = samples[samples.size() - 2];
  EXPECT_LT((samples.back().pose - a.pose).norm(), 0.02 * 100.0 * m.period_s());
  for (std::size_t k = 0; k + 1 < samples.size(); ++k) EXPECT_FALSE(samples[k].end_of_program);
}

TEST(CoarseInterpolator, CycleTimeMatchesTheTrapezoid) {
  const auto m = testing::test_machine(500.0, 5000.0);
  // 100 mm at 100 mm/s, a = 5000: t = L/v + v/a = 1.0 + 0.02 s
  const PipelineRun r = run(m, {line_coarse_interpolator(xyz(0, 0, 0), xyz(100, 0, 0), 100.0)}, xyz(0, 0, 0));
  const double t = r.samples.back().t_s;
  EXPECT_NEAR(t, 1.02, m.period_s());
}

TEST(CoarseInterpolator, ShortSegmentsAreConsumedSeveralPerPeriod) {
  auto m = testing::test_machine();
  // 0.001 mm segments in G1 run exact-stop: each takes 2·sqrt(L/a) ≈ 0.9 ms
  // here; with v·T ≫ L what matters is that segment time is not rounded up
  // to whole periods: the total time is the sum of the profiles.
  std::vector<Segment> segs;
  double t_sum = 0.0;
  for (int k = 0; k < 200; ++k) {
    segs.push_back(line_coarse_interpolator(xyz(k * 0.001, 0, 0), xyz((k + 1) * 0.001, 0, 0), 100.0, k + 1));
    // G61 (the segments' default): each runs from rest to rest
    t_sum += Trapezoid::plan(0.001, m.axes[0].max_acceleration, 0.0, 100.0, 0.0).duration();
  }
  const PipelineRun r = run(m, segs, xyz(0, 0, 0));
  EXPECT_NEAR(r.samples.back().t_s, t_sum, m.period_s());
  EXPECT_EQ(r.sum[0], 200);
}

TEST(CoarseInterpolator, SumOfIncrementsEqualsCommandedStepsOnRandomPrograms) {
  const auto m = testing::test_machine();
  std::mt19937_64 rng(20261122);
  std::uniform_real_distribution<double> ux(0.0, 100.0), uf(1.0, 400.0);
  const int programs = 20;
  for (int p = 0; p < programs; ++p) {
    std::vector<Segment> segs;
    Pose at = xyz(ux(rng), ux(rng), ux(rng));
    const Pose start = at;
    const int n = 1 + static_cast<int>(rng() % 30);
    for (int k = 0; k < n; ++k) {
      const Pose to = xyz(ux(rng) * (k % 3 == 0 ? 0.001 : 1.0), ux(rng), ux(rng) * 0.1);
      Segment s = line_coarse_interpolator(at, to, uf(rng));
      s.end[5] = at[5] + ux(rng);  // C moves too
      segs.push_back(s);
      at = s.end;
    }
    const PipelineRun r = run(m, segs, start);
    for (int a = 0; a < kAxisCount; ++a) {
      EXPECT_EQ(r.sum[a], r.commanded[a]) << "program " << p << " axis " << a;
      EXPECT_EQ(r.sum[a], std::llround(at[a] * 1000.0)) << "program " << p << " axis " << a;
    }
    EXPECT_LE(r.max_abs_inc, static_cast<std::int32_t>(m.dda.max_pulses()));
  }
}

TEST(CoarseInterpolator, CommandedMotionStaysWithinAxisLimits) {
  const auto m = testing::test_machine(200.0, 2000.0);
  std::vector<Segment> segs = {line_coarse_interpolator(xyz(0, 0, 0), xyz(100, 50, 0), 1000.0),
                               line_coarse_interpolator(xyz(100, 50, 0), xyz(10, 60, 20), 1000.0)};
  Segment rapid = line_coarse_interpolator(xyz(10, 60, 20), xyz(300, 60, 20), 0.0);
  rapid.kind = MotionKind::Rapid;
  segs.push_back(rapid);
  const PipelineRun r = run(m, segs, xyz(0, 0, 0));
  MotionStats st(m.period_s(), xyz(0, 0, 0));
  for (const auto& s : r.samples) st.add(s.pose);
  st.finish();
  for (int a = 0; a < 3; ++a) {
    EXPECT_LE(st.peak_velocity()[a], 200.0 * (1 + 1e-9)) << a;
    // sampled second differences of a trapezoid never exceed a
    EXPECT_LE(st.peak_acceleration()[a], 2000.0 * (1 + 1e-6)) << a;
  }
  // the rapid reaches the axis limit
  EXPECT_GT(st.peak_velocity()[0], 199.0);
}

TEST(CoarseInterpolator, DwellHoldsPositionForItsTime) {
  const auto m = testing::test_machine();
  Segment d;
  d.kind = MotionKind::Dwell;
  d.start = d.end = xyz(5, 5, 5);
  d.dwell_s = 0.5;
  d.laser = LaserMode::Constant;  // percussion drilling: fires while standing
  d.power_pct = 60.0;
  Segment d4 = d;
  d4.laser = LaserMode::Dynamic;  // M4 at speed 0: no power
  const PipelineRun r = run(m, {d, d4}, xyz(5, 5, 5));
  EXPECT_NEAR(r.samples.back().t_s, 1.0, m.period_s());
  for (const auto& s : r.samples) {
    EXPECT_EQ(s.pose, xyz(5, 5, 5));
    if (s.end_of_program) continue;
    EXPECT_EQ(s.power_pct, s.t_s <= 0.5 ? 60.0f : 0.0f) << s.t_s;
  }
}

TEST(CoarseInterpolator, LaserPowerFollowsModes) {
  const auto m = testing::test_machine();
  Segment cut = line_coarse_interpolator(xyz(0, 0, 0), xyz(50, 0, 0), 100.0);
  cut.laser = LaserMode::Dynamic;
  cut.power_pct = 80.0;
  Segment rapid = line_coarse_interpolator(xyz(50, 0, 0), xyz(60, 0, 0), 0.0);
  rapid.kind = MotionKind::Rapid;
  rapid.laser = LaserMode::Constant;  // still off on a rapid
  rapid.power_pct = 80.0;
  const PipelineRun r = run(m, {cut, rapid}, xyz(0, 0, 0));
  float peak = 0.0f;
  bool ramp_seen = false;
  for (const auto& s : r.samples) {
    if (s.kind == MotionKind::Rapid) {
      EXPECT_EQ(s.power_pct, 0.0f);
    }
    if (s.kind == MotionKind::Linear) {
      EXPECT_NEAR(s.power_pct, 80.0 * s.speed / 100.0, 1e-3);
      EXPECT_EQ(s.power_cap_pct, 80.0f);  // M4: the RT kernel scales by K up to S
      peak = std::max(peak, s.power_pct);
      ramp_seen = ramp_seen || (s.power_pct > 1.0f && s.power_pct < 79.0f);
    }
  }
  EXPECT_NEAR(peak, 80.0f, 1e-3);
  EXPECT_TRUE(ramp_seen);
  EXPECT_EQ(r.samples.back().power_pct, 0.0f);
}

// Each sample carries its segment's outputs word (digital outputs, then the
// assist gas bits) and analog values: a dwell's gas and outputs as well.
TEST(CoarseInterpolator, SamplesCarryTheirSegmentsOutputsAndGas) {
  const auto m = testing::test_machine();
  Segment a = line_coarse_interpolator(xyz(0, 0, 0), xyz(20, 0, 0), 100.0);
  a.flood = true;
  Segment d;
  d.kind = MotionKind::Dwell;
  d.start = d.end = xyz(20, 0, 0);
  d.dwell_s = 0.2;
  d.mist = true;
  d.digital_out = 0b1001;
  d.analog_out[3] = 7.0f;
  const PipelineRun r = run(m, {a, d}, xyz(0, 0, 0));
  bool seen_line = false, seen_dwell = false;
  for (const auto& s : r.samples) {
    if (s.end_of_program) continue;
    if (s.kind == MotionKind::Linear) {
      seen_line = true;
      EXPECT_EQ(s.outputs, kOutputFlood) << s.t_s;
      EXPECT_EQ(s.analog[3], 0.0f);
    } else {
      seen_dwell = true;
      EXPECT_EQ(s.outputs, 0b1001u | kOutputMist) << s.t_s;
      EXPECT_EQ(s.analog[3], 7.0f);
    }
  }
  EXPECT_TRUE(seen_line && seen_dwell);
}

TEST(StepQuantizer, ClampedStepsAreCarriedNotLost) {
  auto m = testing::test_machine();
  m.dda = DdaConfig{4, 30};  // at most 15 steps per period
  StepQuantizer q(m, xyz(0, 0, 0));
  PeriodSample s;
  s.pose = xyz(0.1, 0, 0);  // 100 steps owed at once
  PeriodIncrement inc = q.quantize(s);
  EXPECT_EQ(inc.steps[0], 15);
  std::int64_t sum = inc.steps[0];
  int periods = 1;
  while (q.owed()) {
    inc = q.pay_owed(s);
    EXPECT_LE(std::abs(inc.steps[0]), 15);
    sum += inc.steps[0];
    ++periods;
  }
  EXPECT_EQ(sum, 100);
  EXPECT_EQ(periods, 7);  // ceil(100 / 15)
}

}  // namespace
}  // namespace lcnc

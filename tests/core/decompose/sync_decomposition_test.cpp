// The time-synchronous decomposition: S1 + S2 = S at every instant, the
// limits and the field never exceeded, infeasible speeds reported with the
// highest feasible one, and the paper's case.
#include "decompose/sync_decomposition.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "common/error.h"
#include "core/dxf/dxf_test_util.h"
#include "decompose/part_decomposition.h"
#include "decompose_test_util.h"

namespace lcnc::decompose {
namespace {

Options sync_options(double speed_mm_s) {
  Options o;
  o.speed_mm_s = speed_mm_s;
  return o;
}

// Linear interpolation of a row sequence at time t (the machine's view
// between table rows).
Vec2 lerp(const std::vector<Vec2>& x, const std::vector<double>& t, double at) {
  const auto it = std::upper_bound(t.begin(), t.end(), at);
  const std::size_t i = std::clamp<std::size_t>(static_cast<std::size_t>(it - t.begin()), 1, t.size() - 1);
  const double f = (at - t[i - 1]) / (t[i] - t[i - 1]);
  return x[i - 1] + f * (x[i] - x[i - 1]);
}

TEST(SyncDecomposition, MainPlusAuxEqualsTheContourAtEveryInstant) {
  Result<PartResult> r = decompose_file(test::sample_part(), sync_options(100.0));
  ASSERT_TRUE(r.ok()) << r.error().to_string();
  std::mt19937 rng(7);
  for (const ContourResult& c : r->contours) {
    const KinematicsTable& t = c.table;
    EXPECT_LE(c.peaks.exactness, 1e-9);
    std::vector<Vec2> aux(t.size());
    for (std::size_t i = 0; i < t.size(); ++i) aux[i] = t.aux(i);
    std::uniform_real_distribution<double> when(0.0, t.t_s.back());
    for (int k = 0; k < 2000; ++k) {
      const double at = when(rng);
      const Vec2 s = lerp(t.beam, t.t_s, at);
      EXPECT_LE((lerp(t.main, t.t_s, at) + lerp(aux, t.t_s, at) - s).norm(), kExactness_mm);
    }
    // The beam runs the contour at constant speed: row spacing Δt, chord ≤ Δ.
    const double dt = c.polyline.step_mm / 100.0;
    EXPECT_NEAR(t.t_s[1] - t.t_s[0], dt, 1e-15);
  }
}

TEST(SyncDecomposition, MainAxesStartAndEndAtRestWithTheAuxCentred) {
  Result<PartResult> r = decompose_file(test::dxf_data("arc_slot.dxf"), sync_options(100.0));
  ASSERT_TRUE(r.ok());
  const KinematicsTable& t = r->contours[0].table;
  EXPECT_EQ(t.aux(0), Vec2::Zero());
  EXPECT_LE(t.aux(t.size() - 1).norm(), 1e-12);
  EXPECT_LE((t.main[1] - t.main[0]).norm(), 1e-12);
  EXPECT_EQ(t.v_main[0], 0.0);
  EXPECT_LE(t.v_main.back(), 1e-6);
}

// Property: over random parts, speeds, fields and limits (fixed seed), every
// decomposition either keeps all limits or is refused — never a table that
// breaks one. LCNC_FUZZ_N scales it.
TEST(SyncDecomposition, LimitsAndFieldAreNeverExceeded) {
  const std::string files[] = {"line_square.dxf",   "arc_slot.dxf",        "lwpolyline_bulge.dxf",
                               "spline_closed.dxf", "polyline_vertex.dxf", "insert_array.dxf"};
  const char* env = std::getenv("LCNC_FUZZ_N");
  const int n = env ? std::atoi(env) : 24;
  std::mt19937 rng(20261122);
  int feasible = 0;
  for (int it = 0; it < n; ++it) {
    Options o;
    o.speed_mm_s = std::uniform_real_distribution<double>(20, 600)(rng);
    o.main_accel_mm_s2 = std::uniform_real_distribution<double>(0.1, 1.0)(rng) * kG_mm_s2;
    o.aux_half_field_mm = std::uniform_real_distribution<double>(0.2, 10)(rng);
    o.aux_speed_mm_s = std::uniform_real_distribution<double>(800, 6000)(rng);
    const std::string& f = files[rng() % std::size(files)];
    Result<PartResult> r = decompose_file(test::dxf_data(f), o, 0.02);
    if (!r.ok()) {
      EXPECT_EQ(r.error().code, ErrorCode::DecomposeInfeasible) << r.error().to_string();
      continue;
    }
    ++feasible;
    for (const ContourResult& c : r->contours) {
      const Peaks& p = c.peaks;
      EXPECT_LE(p.a_main, o.main_accel_mm_s2) << f;
      EXPECT_LE(p.v_main, o.main_speed_mm_s) << f;
      EXPECT_LE(p.v_aux, o.aux_speed_mm_s) << f;
      EXPECT_LE(p.aux_excursion, o.aux_half_field_mm) << f;
      EXPECT_LE(p.exactness, kExactness_mm) << f;
      EXPECT_TRUE(c.exceeded.empty());
      // The filter's guarantee: |a1| ≤ 2 vk / τ.
      EXPECT_LE(p.a_main, 2 * o.speed_mm_s / c.tau_s * (1 + 1e-9));
    }
  }
  EXPECT_GT(feasible, n / 4);
}

TEST(SyncDecomposition, InfeasibleSpeedIsReportedWithTheHighestFeasible) {
  Options o = sync_options(1000.0);  // 60 m/min in a ±5 mm field
  Result<PartResult> r = decompose_file(test::sample_part(), o);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, ErrorCode::DecomposeInfeasible);
  EXPECT_MENTIONS(
      r.error(),
      "contour 1 (LWPOLYLINE at DXF line 59, layer CUT): contour speed 1000.0 mm/s (60.00 m/min) exceeds");
  EXPECT_MENTIONS(r.error(), "the highest feasible is");
  // The highest feasible speed of that contour works, and a little more does not.
  Result<PreparedPart> prep = prepare_part(test::read_ok(test::sample_part()), 0.01);
  ASSERT_TRUE(prep.ok());
  const dxf::Polyline& outer = prep->polylines[0];
  const double best = highest_feasible_speed(outer, o);
  ASSERT_GT(best, 100.0);
  ASSERT_LT(best, 1000.0);
  Options at_best = o;
  at_best.speed_mm_s = best;
  EXPECT_TRUE(sync_decompose(outer, at_best, "outer").ok());
  Options above = o;
  above.speed_mm_s = best * (1 + 3 * kSpeedSearchRel);
  EXPECT_FALSE(sync_decompose(outer, above, "outer").ok());
}

TEST(SyncDecomposition, ContourFasterThanTheMainAxesIsInfeasible) {
  // On a 30 mm straight edge the main axes must follow at nearly the contour
  // speed when the field is ±1 mm.
  Options o = sync_options(400.0);
  o.main_speed_mm_s = 300.0;
  o.main_accel_mm_s2 = 100 * kG_mm_s2;  // only the speed can fail
  o.aux_half_field_mm = 1.0;
  Result<PartResult> r = decompose_file(test::dxf_data("lwpolyline_bulge.dxf"), o);
  ASSERT_FALSE(r.ok());
  EXPECT_MENTIONS(r.error(), "exceeds the main-axis speed limit");
}

// The paper's case in the synchronous mode: 6 m/min, effective acceleration
// ≤ 1 g on the sample part, main axes within 0.5 g and far below a
// main-axes-only machine on the same part at the same speed.
TEST(SyncDecomposition, SeedCaseSixMetresPerMinute) {
  Result<PartResult> r = decompose_file(test::sample_part(), sync_options(100.0));
  ASSERT_TRUE(r.ok());
  double a_eff = 0, a_main = 0;
  for (const ContourResult& c : r->contours) {
    a_eff = std::max(a_eff, c.peaks.a_eff);
    a_main = std::max(a_main, c.peaks.a_main);
  }
  EXPECT_LE(a_eff, kG_mm_s2);
  EXPECT_LE(a_main, kDefaultMainAccel_mm_s2);
  // a_eff is what a main-axes-only machine needs at this contour speed.
  EXPECT_GE(a_eff / a_main, 5.0);
}

TEST(SyncDecomposition, ShortestLeadInUsesTheMainAxesUpToTheirLimit) {
  Options smooth = sync_options(150.0);
  Options shortest = smooth;
  shortest.goal = SyncGoal::ShortestLeadIn;
  Result<PartResult> a = decompose_file(test::dxf_data("lwpolyline_bulge.dxf"), smooth);
  Result<PartResult> b = decompose_file(test::dxf_data("lwpolyline_bulge.dxf"), shortest);
  ASSERT_TRUE(a.ok() && b.ok());
  const ContourResult& ca = a->contours[0];
  const ContourResult& cb = b->contours[0];
  EXPECT_LT(cb.tau_s, ca.tau_s);
  EXPECT_LT(cb.peaks.duration_s, ca.peaks.duration_s);
  EXPECT_LE(cb.peaks.a_main, kDefaultMainAccel_mm_s2);
  EXPECT_GT(cb.peaks.a_main, 0.9 * kDefaultMainAccel_mm_s2);  // within the 1 % search
  EXPECT_LT(cb.peaks.aux_excursion, ca.peaks.aux_excursion);
}

TEST(SyncDecomposition, OneMicronStepWorks) {
  Result<PartResult> r = decompose_file(test::dxf_data("circle.dxf"), sync_options(100.0), 0.001);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r->points, 25133u);
  EXPECT_LE(r->contours[0].peaks.a_main, kDefaultMainAccel_mm_s2);
}

TEST(SyncDecomposition, BadOptionsAreRefused) {
  Options o = sync_options(0.0);
  Result<PartResult> r = decompose_file(test::dxf_data("circle.dxf"), o);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, ErrorCode::DecomposeBadOption);
  EXPECT_MENTIONS(r.error(), "contour speed");
}

}  // namespace
}  // namespace lcnc::decompose

// The paper's decomposition (Kondratenko et al. 2015 eq. 1–13) and the paper's test case.
#include "decompose/seed_decomposition.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "common/error.h"
#include "core/dxf/dxf_test_util.h"
#include "decompose/part_decomposition.h"
#include "decompose_test_util.h"

namespace lcnc::decompose {
namespace {

double turn_deg(const Vec2& a, const Vec2& b, const Vec2& c) {
  const Vec2 d1 = b - a, d2 = c - b;
  const double l = d1.norm() * d2.norm();
  if (l == 0) return 0;
  return std::acos(std::clamp(d1.dot(d2) / l, -1.0, 1.0)) * 180 / std::numbers::pi;
}

Options seed_options(double speed = 100.0) {
  Options o;
  o.mode = Mode::Seed;
  o.speed_mm_s = speed;
  return o;
}

TEST(SeedDecomposition, SmoothingLeavesNoTurnAboveTheCriticalAngle) {
  Result<PartResult> r = decompose_file(test::dxf_data("line_square.dxf"), seed_options(), 0.05);
  ASSERT_TRUE(r.ok()) << r.error().to_string();
  const KinematicsTable& t = r->contours[0].table;
  const std::size_t n = t.size() - 1;  // row n is row 0 again
  for (std::size_t j = 0; j < n; ++j) {
    const double turn = turn_deg(t.main[(j + n - 1) % n], t.main[j], t.main[(j + 1) % n]);
    EXPECT_LE(turn, kDefaultCriticalAngle_deg + 1e-9) << "vertex " << j;
  }
  // Corners were cut: the auxiliary axes moved.
  EXPECT_GT(r->contours[0].peaks.aux_excursion, 0.01);
}

TEST(SeedDecomposition, EquationsSixToThirteen) {
  Result<PartResult> r = decompose_file(test::dxf_data("line_square.dxf"), seed_options(100.0), 0.05);
  ASSERT_TRUE(r.ok());
  const KinematicsTable& t = r->contours[0].table;
  EXPECT_EQ(t.v_main[0], 50.0);  // eq. 6: v0 = vk / 2
  EXPECT_EQ(t.v_aux[0], 50.0);
  for (std::size_t i = 1; i < t.size(); ++i) {
    const Vec2 ds = t.beam[i] - t.beam[i - 1];
    const Vec2 ds1 = t.main[i] - t.main[i - 1];
    const double h1 = ds1.norm(), h2 = (ds - ds1).norm();   // S2 = S − S1, step by step
    const double k1 = h1 / (h1 + h2), k2 = h2 / (h1 + h2);  // eq. 7, 8
    EXPECT_NEAR(t.v_main[i], 2 * 50.0 * k1, 1e-9);          // eq. 9
    EXPECT_NEAR(t.v_aux[i], 2 * 50.0 * k2, 1e-9);           // eq. 10
    EXPECT_NEAR(t.v_main[i] + t.v_aux[i], 100.0, 1e-9);
    EXPECT_NEAR(t.t_s[i] - t.t_s[i - 1], (h1 + h2) / 100.0, 1e-15);  // eq. 11
    const double dt = t.t_s[i] - t.t_s[i - 1];
    EXPECT_NEAR(t.at_main[i], (t.v_main[i] - t.v_main[i - 1]) / dt, 1e-6);  // eq. 12
    EXPECT_NEAR(t.at_aux[i], (t.v_aux[i] - t.v_aux[i - 1]) / dt, 1e-6);     // eq. 13
    EXPECT_NEAR((t.main[i] + t.aux(i) - t.beam[i]).norm(), 0.0, 1e-12);
  }
  EXPECT_TRUE(t.beam.back().isApprox(t.beam.front()));  // the loop closes
}

TEST(SeedDecomposition, UnchangedStepsRunTheMainAxesAtContourSpeed) {
  // A large circle turns 0.06° per 0.01 mm step: below the critical angle,
  // so S1 = S and the main axes carry the whole speed.
  Result<PartResult> r = decompose_file(test::dxf_data("units_inch.dxf"), seed_options(100.0));
  ASSERT_TRUE(r.ok());
  const Peaks& p = r->contours[0].peaks;
  EXPECT_EQ(p.aux_excursion, 0.0);
  EXPECT_NEAR(p.v_main, 100.0, 1e-6);
}

// Seed 004: "at a contour speed of 6 m/min the effective resulting
// acceleration does not exceed 9 m/s², i.e. 1 g" (Fig. 8) — on the sample
// part (fillets ≥ 2.5 mm, the spline's tightest bend ~2.5 mm).
TEST(SeedDecomposition, SeedCaseSixMetresPerMinuteStaysUnderOneG) {
  Result<PartResult> r = decompose_file(test::sample_part(), seed_options(100.0));
  ASSERT_TRUE(r.ok()) << r.error().to_string();
  double a_eff = 0;
  for (const ContourResult& c : r->contours) a_eff = std::max(a_eff, c.peaks.a_eff);
  EXPECT_LE(a_eff, kG_mm_s2);
  EXPECT_GT(a_eff, 0.1 * kG_mm_s2);
}

TEST(SeedDecomposition, ReportsTheLimitsItBreaks) {
  // Sharp corners at 6 m/min: the paper's S1 turns them on a ~0.57 mm radius
  // (1° per 0.01 mm), far above 0.5 g — reported, not hidden.
  Result<PartResult> r = decompose_file(test::dxf_data("line_square.dxf"), seed_options(100.0));
  ASSERT_TRUE(r.ok());
  ASSERT_FALSE(r->contours[0].exceeded.empty());
  EXPECT_NE(r->contours[0].exceeded[0].find("main acceleration"), std::string::npos);
}

TEST(SeedDecomposition, AContourTooSmallForTheCriticalAngleIsAnError) {
  // 8 points cannot turn 360° at ≤ 1° each: the walk would shrink the circle.
  Result<PartResult> r = decompose_file(test::dxf_data("circle.dxf"), seed_options(), 5.0);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, ErrorCode::DecomposeBadOption);
  EXPECT_MENTIONS(r.error(), "contour 1 (CIRCLE");
  EXPECT_MENTIONS(r.error(), "cannot turn 360°");
}

}  // namespace
}  // namespace lcnc::decompose

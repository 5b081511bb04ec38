#include "kinematics/orientation_interpolation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <numbers>
#include <random>

#include "kinematics_test_util.h"
#include "support/test_scale.h"

namespace lcnc {
namespace {

using testing::end_c_for_pole_distance;

OrientationMove make_orientation_interpolation(OrientationMethod m, RotaryJoints a, RotaryJoints b) {
  Result<OrientationMove> r = OrientationMove::between_joints(m, a, b, RotaryLimits{});
  EXPECT_TRUE(r.ok()) << r.error().to_string();
  return *r;
}

constexpr TimeLaw kLaw{1.0, 0.25};  // 1 s, 0.25 s ramps: 80°/s along a 60° arc
constexpr double kDt = 1e-4;

TEST(OrientationInterpolation, VectorIsTheGreatCircle) {
  const OrientationMove m =
      make_orientation_interpolation(OrientationMethod::Vector, {20.0, 10.0}, {60.0, 100.0});
  const OrientationReport r = evaluate(m, kLaw, kDt);
  EXPECT_LT(r.max_error_deg, 1e-9);
  EXPECT_LT(angle_between_deg(m.axis_at(1.0), tool_axis(60.0, 100.0)), 1e-9);
  EXPECT_NEAR(m.end_joints().a_deg, 60.0, 1e-9);
  EXPECT_NEAR(m.end_joints().c_deg, 100.0, 1e-9);
}

// Random moves, both branches: the vector and pole-smoothed interpolators
// follow the great circle and end on the programmed axis; joints are
// continuous (C turns by less than 2° per 1/2000 of a move that stays ≥ 2°
// from the pole).
TEST(OrientationInterpolation, RandomMovesFollowTheGreatCircle) {
  const RotaryLimits lim;
  std::mt19937 rng(808);
  std::uniform_real_distribution<double> a(-90.0, 90.0), c(-720.0, 720.0);
  int checked = 0;
  for (int i = 0; i < 200; ++i) {
    const RotaryJoints start{a(rng), c(rng)};
    const Vec3 k1 = tool_axis(a(rng), c(rng));
    if (angle_between_deg(tool_axis(start), k1) > 170.0) continue;
    for (OrientationMethod m : {OrientationMethod::Vector, OrientationMethod::PoleSmoothed}) {
      const Result<OrientationMove> mv = OrientationMove::to_axis(m, start, k1, lim);
      if (!mv.ok()) {  // a great circle bulging past ±95°
        EXPECT_EQ(mv.error().code, ErrorCode::GcodeBeyondTravel);
        continue;
      }
      EXPECT_NEAR(mv->start_joints().a_deg, start.a_deg, 1e-9);
      EXPECT_NEAR(mv->start_joints().c_deg, start.c_deg, 1e-9);
      EXPECT_LT(angle_between_deg(mv->axis_at(1.0), k1), 1e-9);
      RotaryJoints prev = mv->joints_at(0.0);
      for (int k = 1; k <= 2000; ++k) {
        const double u = k / 2000.0;
        ASSERT_LT(angle_between_deg(mv->axis_at(u), mv->ideal_axis_at(u)), 1e-9);
        const RotaryJoints j = mv->joints_at(u);
        if (mv->pole_distance_deg() >= 2.0) {
          ASSERT_LT(std::abs(j.c_deg - prev.c_deg), 2.0) << i << " u " << u;
        }
        ASSERT_LT(std::abs(j.a_deg - prev.a_deg), 1.0) << i << " u " << u;
        prev = j;
      }
      ++checked;
    }
  }
  EXPECT_GT(checked, 300);
}

TEST(OrientationInterpolation, RateIsTheDerivativeOfTheJoints) {
  const OrientationMove m =
      make_orientation_interpolation(OrientationMethod::JointLinear, {20.0, 10.0}, {60.0, 100.0});
  EXPECT_NEAR(m.rate_at(0.3).a_deg, 40.0, 1e-6);
  EXPECT_NEAR(m.rate_at(1.0).c_deg, 90.0, 1e-6);  // one-sided at the end
  const OrientationMove v =
      make_orientation_interpolation(OrientationMethod::Vector, {20.0, 10.0}, {60.0, 100.0});
  const double h = 1e-4;
  const double dc = (v.joints_at(0.5 + h).c_deg - v.joints_at(0.5 - h).c_deg) / (2 * h);
  EXPECT_NEAR(v.rate_at(0.5).c_deg, dc, 1e-3 * std::abs(dc));
}

TEST(OrientationInterpolation, JointLinearLeavesTheGreatCircle) {
  const OrientationMove m =
      make_orientation_interpolation(OrientationMethod::JointLinear, {30.0, 0.0}, {30.0, 180.0});
  const OrientationReport r = evaluate(m, kLaw, kDt);
  EXPECT_GT(r.max_error_deg, 25.0);  // mid-move at (30°, 90°) instead of the pole
  EXPECT_NEAR(r.samples.back().c_deg, 180.0, 1e-12);
  EXPECT_TRUE(r.within(RotaryLimits{}));
}

// On a path through A = 0 the improved interpolator keeps C within
// its velocity and acceleration limits with orientation error ≤ 0.01°, while
// the plain vector interpolator exceeds them.
TEST(OrientationInterpolation, PoleSmoothedBoundsCThroughThePole) {
  const RotaryLimits lim;
  for (double delta_deg : {0.0, 0.001, 0.005, 0.0099}) {
    const RotaryJoints a{30.0, 0.0}, b{30.0, end_c_for_pole_distance(delta_deg)};
    const OrientationMove vec = make_orientation_interpolation(OrientationMethod::Vector, a, b);
    const OrientationMove smooth = make_orientation_interpolation(OrientationMethod::PoleSmoothed, a, b);
    EXPECT_NEAR(vec.pole_distance_deg(), delta_deg, 1e-9);
    EXPECT_TRUE(smooth.pole_snapped());

    const OrientationReport rv = evaluate(vec, kLaw, kDt);
    const OrientationReport rs = evaluate(smooth, kLaw, kDt);
    EXPECT_GT(rv.peak_c_vel_deg_s, 100.0 * lim.c_max_velocity_deg_s) << "δ " << delta_deg;
    EXPECT_FALSE(rv.within(lim));

    EXPECT_TRUE(rs.within(lim)) << "δ " << delta_deg << ": C " << rs.peak_c_vel_deg_s << " °/s, "
                                << rs.peak_c_acc_deg_s2 << " °/s², A " << rs.peak_a_vel_deg_s << " °/s, "
                                << rs.peak_a_acc_deg_s2 << " °/s²";
    EXPECT_LE(rs.max_error_deg, kin::kOrientationToleranceDeg);
    EXPECT_LE(rs.max_error_deg, delta_deg + 1e-9);
    // Through the pole on the other branch: A changes sign, C hardly moves.
    EXPECT_NEAR(smooth.end_joints().a_deg, -30.0, 1e-9);
    EXPECT_LT(rs.peak_c_vel_deg_s, 1.0);
    // Same end orientation as programmed.
    EXPECT_LT(angle_between_deg(smooth.axis_at(1.0), tool_axis(b)), 1e-9);
  }
}

// Random great circles passing the pole within the tolerance, the pole
// anywhere inside the move: the improved interpolator never leaves the
// tolerance, ends exactly at the programmed axis, is never slower under the
// limits than the plain vector interpolator, and with the pole ≥ 20° from
// both ends (full core and taper) keeps A and C within their limits.
TEST(OrientationInterpolation, PoleSmoothedPropertiesNearThePole) {
  const RotaryLimits lim;
  std::mt19937 rng(88);
  std::uniform_real_distribution<double> delta(0.0, 0.0099), psi(0.0, 360.0), before(2.0, 80.0),
      after(2.0, 80.0), c_prev(-400.0, 400.0);
  const int n = testing::scaled(60);
  for (int i = 0; i < n; ++i) {
    const double d = delta(rng) * kRadPerDeg, p = psi(rng) * kRadPerDeg;
    const Vec3 m(std::sin(d) * std::cos(p), std::sin(d) * std::sin(p), std::cos(d));
    const Vec3 t(-std::sin(p), std::cos(p), 0.0);
    const double a0 = -before(rng) * kRadPerDeg, a1 = after(rng) * kRadPerDeg;
    const Vec3 k0 = std::cos(a0) * m + std::sin(a0) * t, k1 = std::cos(a1) * m + std::sin(a1) * t;
    const Result<RotaryJoints> start = choose_rotary(k0, {0.0, c_prev(rng)}, lim);
    ASSERT_TRUE(start.ok());
    const auto smooth = OrientationMove::to_axis(OrientationMethod::PoleSmoothed, *start, k1, lim);
    const auto vec = OrientationMove::to_axis(OrientationMethod::Vector, *start, k1, lim);
    ASSERT_TRUE(smooth.ok() && vec.ok()) << i;
    EXPECT_LT(angle_between_deg(smooth->axis_at(1.0), k1), 1e-9) << i;
    EXPECT_GE(smooth->max_u_rate(lim), vec->max_u_rate(lim)) << i;
    const OrientationReport r = evaluate(*smooth, TimeLaw{2.0, 0.25}, 2e-4);
    EXPECT_LE(r.max_error_deg, kin::kOrientationToleranceDeg) << i;
    if (std::min(-a0, a1) >= 20.0 * kRadPerDeg) {
      EXPECT_TRUE(smooth->pole_snapped()) << i;
      EXPECT_TRUE(r.within(lim)) << i << ": C " << r.peak_c_vel_deg_s << " °/s " << r.peak_c_acc_deg_s2
                                 << " °/s²";
    }
  }
}

TEST(OrientationInterpolation, SnapNeedsBothSignsOfA) {
  RotaryLimits lim;
  lim.a_min_deg = 0.0;  // tilts one way only: the pole pass cannot flip A
  const auto m = OrientationMove::between_joints(OrientationMethod::PoleSmoothed, {30.0, 0.0},
                                                 {30.0, end_c_for_pole_distance(0.005)}, lim);
  ASSERT_TRUE(m.ok()) << m.error().to_string();
  EXPECT_FALSE(m->pole_snapped());
  EXPECT_GE(m->end_joints().a_deg, 0.0);
}

TEST(OrientationInterpolation, PoleFartherThanToleranceStaysExactAndRetimes) {
  const RotaryLimits lim;
  const RotaryJoints a{30.0, 0.0}, b{30.0, end_c_for_pole_distance(0.5)};
  const OrientationMove smooth = make_orientation_interpolation(OrientationMethod::PoleSmoothed, a, b);
  EXPECT_FALSE(smooth.pole_snapped());
  const OrientationReport r = evaluate(smooth, kLaw, kDt);
  EXPECT_LT(r.max_error_deg, 1e-9);
  EXPECT_FALSE(r.within(lim));  // C turns 180° within ~1° of arc at full speed
  // Re-timed to max_u_rate: C's speed within its limit during the cruise.
  const double rate = smooth.max_u_rate(lim);
  ASSERT_GT(rate, 0.0);
  const TimeLaw slow{1.0 / (rate * (1.0 - 0.01)), 0.01};
  const OrientationReport rs = evaluate(smooth, slow, 1e-3);
  EXPECT_LE(rs.peak_c_vel_deg_s, lim.c_max_velocity_deg_s * 1.01);
  // A snapped move needs no re-timing at the same time law.
  const OrientationMove snapped = make_orientation_interpolation(OrientationMethod::PoleSmoothed, a,
                                                                 {30.0, end_c_for_pole_distance(0.005)});
  EXPECT_GT(snapped.max_u_rate(lim), 50.0 * rate);  // A-limited (3/s) vs C-limited
}

TEST(OrientationInterpolation, StartOnThePoleLeavesWithTheNearestC) {
  const OrientationMove m =
      make_orientation_interpolation(OrientationMethod::Vector, {0.0, 77.0}, {40.0, 10.0});
  EXPECT_NEAR(m.start_joints().a_deg, 0.0, 1e-9);
  EXPECT_NEAR(m.start_joints().c_deg, 10.0, 1e-6);  // departure C (10°, not 190°)
  EXPECT_NEAR(m.end_joints().c_deg, 10.0, 1e-6);
  const OrientationReport r = evaluate(m, kLaw, kDt);
  EXPECT_LT(r.max_error_deg, 1e-9);
  EXPECT_LT(r.peak_c_vel_deg_s, 1e-6);
}

TEST(OrientationInterpolation, ToAxisEndsAtTheNearestSolution) {
  const Result<OrientationMove> m = OrientationMove::to_axis(OrientationMethod::JointLinear, {10.0, 350.0},
                                                             tool_axis(-20.0, 170.0), RotaryLimits{});
  ASSERT_TRUE(m.ok());
  EXPECT_NEAR(m->end_joints().a_deg, 20.0, 1e-9);
  EXPECT_NEAR(m->end_joints().c_deg, 350.0, 1e-9);
}

TEST(OrientationInterpolation, Errors) {
  // 180° apart: no great circle.
  Result<OrientationMove> m =
      OrientationMove::to_axis(OrientationMethod::Vector, {90.0, 0.0}, Vec3(0.0, 1.0, 0.0), RotaryLimits{});
  ASSERT_FALSE(m.ok());
  EXPECT_EQ(m.error().code, ErrorCode::GcodeBadValue);
  // Negative tolerance.
  m = OrientationMove::between_joints(OrientationMethod::PoleSmoothed, {10.0, 0.0}, {20.0, 0.0},
                                      RotaryLimits{}, -1.0);
  ASSERT_FALSE(m.ok());
  // A great circle between two orientations at 94° bulges past A = 95°.
  m = OrientationMove::between_joints(OrientationMethod::Vector, {-94.0, 0.0}, {-94.0, 150.0},
                                      RotaryLimits{});
  ASSERT_FALSE(m.ok());
  EXPECT_EQ(m.error().code, ErrorCode::GcodeBeyondTravel);
}

TEST(TimeLaw, RestToRestTrapezoid) {
  const TimeLaw law{2.0, 0.25};
  EXPECT_EQ(law.u_at(0.0), 0.0);
  EXPECT_EQ(law.u_at(2.0), 1.0);
  EXPECT_NEAR(law.u_at(1.0), 0.5, 1e-12);
  double prev = 0.0;
  for (int i = 1; i <= 200; ++i) {
    const double u = law.u_at(i * 0.01);
    EXPECT_GE(u, prev);
    prev = u;
  }
}

}  // namespace
}  // namespace lcnc

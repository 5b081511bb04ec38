#include "kinematics/orientation_retiming.h"
#include "kinematics_test_util.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

namespace lcnc {
namespace {

using testing::end_c_for_pole_distance;

// The pole 0.5° away (beyond the 0.01° tolerance): the improved interpolator
// stays on the great circle, and the re-timed law keeps C within its limits.
TEST(OrientationRetiming, SlowsThePolePassIntoTheLimits) {
  const RotaryLimits lim;
  const Result<OrientationMove> m = OrientationMove::between_joints(
      OrientationMethod::PoleSmoothed, {30.0, 0.0}, {30.0, end_c_for_pole_distance(0.5)}, lim);
  ASSERT_TRUE(m.ok());
  ASSERT_FALSE(m->pole_snapped());
  const RetimedLaw law = retime(*m, lim, 4.0 / 3.0, 16.0 / 3.0);
  const OrientationReport r = evaluate(*m, law, 1e-4);
  EXPECT_LT(r.max_error_deg, 1e-9);
  // Within the limits up to the grid's discretisation.
  EXPECT_LE(r.peak_c_vel_deg_s, 1.01 * lim.c_max_velocity_deg_s);
  EXPECT_LE(r.peak_c_acc_deg_s2, 1.05 * lim.c_max_accel_deg_s2);
  EXPECT_LE(r.peak_a_vel_deg_s, 1.01 * lim.a_max_velocity_deg_s);
  // Slower than the nominal 1 s, but only the pole pass is slowed: C's 180°
  // at 360 °/s, 3600 °/s² alone takes ≥ 0.6 s.
  EXPECT_GT(law.duration_s(), 1.0);
  EXPECT_LT(law.duration_s(), 2.5);
}

TEST(OrientationRetiming, ProgrammedCapsRuleAwayFromThePole) {
  const RotaryLimits lim;
  const Result<OrientationMove> m =
      OrientationMove::between_joints(OrientationMethod::JointLinear, {30.0, 0.0}, {30.0, 180.0}, lim);
  ASSERT_TRUE(m.ok());
  // Caps of a 1 s trapezoid with 0.25 s ramps: the same 1 s.
  const RetimedLaw law = retime(*m, lim, 4.0 / 3.0, 16.0 / 3.0);
  EXPECT_NEAR(law.duration_s(), 1.0, 1e-3);
  EXPECT_NEAR(law.peak_u_rate(), 4.0 / 3.0, 1e-9);
  EXPECT_EQ(law.u_at(-1.0), 0.0);
  EXPECT_EQ(law.u_at(law.duration_s()), 1.0);
  double prev = 0.0;
  for (int i = 1; i <= 1000; ++i) {
    const double u = law.u_at(law.duration_s() * i / 1000.0);
    ASSERT_GE(u, prev - 1e-15);
    prev = u;
  }
  // No caps: the limits alone (C 180° at 360 °/s, 3600 °/s² → 0.5 s + ramps).
  const double inf = std::numeric_limits<double>::infinity();
  const RetimedLaw fast = retime(*m, lim, inf, inf);
  EXPECT_LT(fast.duration_s(), 1.0);
  const OrientationReport r = evaluate(*m, fast, 1e-4);
  EXPECT_LE(r.peak_c_vel_deg_s, 1.001 * lim.c_max_velocity_deg_s);
  EXPECT_LE(r.peak_c_acc_deg_s2, 1.05 * lim.c_max_accel_deg_s2);
}

}  // namespace
}  // namespace lcnc

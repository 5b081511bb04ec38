#include "plan/ramp_room.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/plan/test_machine.h"

namespace lcnc {
namespace {

Pose at_x(double x) {
  Pose p = Pose::Zero();
  p[0] = x;
  return p;
}

// X at speed v for two periods, then one more period to `x_next`.
RampRoom room_after(const MachineConfig& m, double v, double dv) {
  const double T = m.period_s();
  RampRoomMeter meter(m, at_x(0.0));
  (void)meter.next(at_x(v * T));
  (void)meter.next(at_x(2 * v * T));
  return meter.next(at_x(3 * v * T + dv * T));
}

// Cruising: the ramp may use the whole acceleration both ways, amax/v.
TEST(RampRoom, ACruiseLeavesTheWholeAccelerationToTheRamp) {
  const MachineConfig m = testing::test_machine();
  const RampRoom r = room_after(m, 100.0, 0.0);
  EXPECT_NEAR(r.r0, 5000.0 / 100.0, 1e-3);
  EXPECT_NEAR(r.down, 0.0, 1e-6);
  EXPECT_NEAR(r.up, 0.0, 1e-6);
}

// Braking at the full deceleration leaves a falling K no room at K = 1
// (f = 1) and the rest at K < 1; a rising K keeps it all.
TEST(RampRoom, FullBrakingLeavesAFallingOverrideNoRoomAtFullSpeed) {
  const MachineConfig m = testing::test_machine();
  const double T = m.period_s();
  const double a = 5000.0, v = 100.0;
  const RampRoom r = room_after(m, v, -a * T);  // dv = −a·T over one period
  // v is the larger of the two periods' speeds: v (before)
  EXPECT_NEAR(r.r0, a / v, 1e-3);
  EXPECT_NEAR(r.down, 1.0, 1e-6);
  EXPECT_NEAR(r.up, 0.0, 1e-6);
}

// Speeding up is the mirror image: a rising K has no room at K = 1.
TEST(RampRoom, FullAccelerationLeavesARisingOverrideNoRoomAtFullSpeed) {
  const MachineConfig m = testing::test_machine();
  const double T = m.period_s();
  const double a = 5000.0, v = 100.0;
  const RampRoom r = room_after(m, v, a * T);
  EXPECT_NEAR(r.r0, a / (v + a * T), 1e-2);
  EXPECT_NEAR(r.up, 1.0, 1e-6);
  EXPECT_NEAR(r.down, 0.0, 1e-6);
}

// An axis at rest puts no bound on the ramp; the other axes do.
TEST(RampRoom, AnAxisAtRestPutsNoBound) {
  const MachineConfig m = testing::test_machine();
  RampRoomMeter meter(m, Pose::Zero());
  const RampRoom r = meter.next(Pose::Zero());
  EXPECT_TRUE(std::isinf(r.r0));
  EXPECT_LT(r.up, 1e-30f);
  EXPECT_LT(r.down, 1e-30f);
}

}  // namespace
}  // namespace lcnc

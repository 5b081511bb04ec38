#include "plan/ramp_room.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

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

// A circle at its centripetal limit, 10° before X turns: X brakes at nearly
// its full acceleration and moves slowly, Y cruises fast. At K = 1 a falling
// K has X's own room, (amax/|v_x|)·(1 − |a_x|/amax), not Y's rate times X's
// share (which would be nearly nothing); at K = 0 it has Y's rate.
TEST(RampRoom, ACircleAtItsLimitKeepsTheRoomOfEachAxis) {
  const MachineConfig m = testing::test_machine();
  const double T = m.period_s(), amax = 5000.0, radius = 20.0;
  const double v = std::sqrt(amax * radius), w = v / radius;
  const auto at = [&](double angle) {
    Pose p = Pose::Zero();
    p[0] = radius * std::cos(angle);
    p[1] = radius * std::sin(angle);
    return p;
  };
  const double end = -10.0 * std::numbers::pi / 180.0;  // X reverses at angle 0
  RampRoomMeter meter(m, at(end - 2 * w * T));
  (void)meter.next(at(end - w * T));
  const RampRoom r = meter.next(at(end));
  const double vx = v * std::sin(10.0 * std::numbers::pi / 180.0);
  const double fx = std::cos(10.0 * std::numbers::pi / 180.0);
  const double vy = v * std::cos(10.0 * std::numbers::pi / 180.0);
  EXPECT_NEAR(r.r0, amax / vy, 0.01 * amax / vy);  // Y's, at K = 0
  const double at_k1 = r.r0 * (1.0 - r.down);
  EXPECT_NEAR(at_k1, amax / vx * (1.0 - fx), 0.02 * amax / vx * (1.0 - fx));
  EXPECT_GT(at_k1, 2.0 * (amax / vy) * (1.0 - fx));  // not Y's rate times X's share
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

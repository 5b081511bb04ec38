#include "plan/increment_guard.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "test_machine.h"

namespace lcnc {
namespace {

// X: vmax 500 mm/s, amax 5000 mm/s², 1 µm steps, T = 75 µs: at most
// ⌊37.5⌋ + 1 = 38 steps a period, and a change of at most ⌊0.028⌋ + 2 = 2.
PeriodIncrement x_steps(std::int32_t d, std::uint32_t line = 7) {
  PeriodIncrement inc;
  inc.steps[0] = d;
  inc.line = line;
  return inc;
}

using testing::at_x;

TEST(IncrementGuard, AdmitsAMoveWithinEveryLimitExactly) {
  const MachineConfig m = testing::test_machine();
  IncrementGuard g(m, at_x(100'000));
  // speed up by 2 steps a period to 38, cruise, slow down to rest
  std::vector<std::int32_t> steps;
  for (std::int32_t d = 2; d <= 38; d += 2) steps.push_back(d);
  steps.insert(steps.end(), 100, 38);
  for (std::int32_t d = 36; d >= 0; d -= 2) steps.push_back(d);
  std::int64_t sum = 0;
  for (const std::int32_t d : steps) {
    ASSERT_TRUE(g.admit(x_steps(d))) << d << ": " << g.error().to_string();
    sum += d;
  }
  EXPECT_EQ(g.position(0), 100'000 + sum);
}

TEST(IncrementGuard, RefusesOnePeriodFasterThanTheVelocityLimit) {
  const MachineConfig m = testing::test_machine();
  IncrementGuard g(m, at_x(100'000));
  for (std::int32_t d = 2; d <= 38; d += 2) ASSERT_TRUE(g.admit(x_steps(d)));
  ASSERT_TRUE(g.admit(x_steps(38)));
  EXPECT_FALSE(g.admit(x_steps(39, 12)));  // 520 mm/s
  EXPECT_EQ(g.error().code, ErrorCode::PlanBeyondLimit);
  EXPECT_EQ(g.error().line, 12u);
  EXPECT_NE(g.error().message.find("axis X"), std::string::npos) << g.error().message;
  EXPECT_NE(g.error().message.find("velocity"), std::string::npos) << g.error().message;
  EXPECT_EQ(g.position(0), 100'000 + 19 * 20 + 38);  // nothing refused is taken
}

// The case a dropped segment made: from rest straight to 255 steps a period.
TEST(IncrementGuard, RefusesAJumpFromRest) {
  const MachineConfig m = testing::test_machine();
  IncrementGuard g(m, at_x(100'000));
  EXPECT_FALSE(g.admit(x_steps(255)));
  EXPECT_EQ(g.error().code, ErrorCode::PlanBeyondLimit);
  // within the velocity limit, but a speed change of 3 steps at once
  IncrementGuard g2(m, at_x(100'000));
  EXPECT_FALSE(g2.admit(x_steps(3)));
  EXPECT_NE(g2.error().message.find("acceleration"), std::string::npos) << g2.error().message;
  IncrementGuard g3(m, at_x(100'000));
  EXPECT_TRUE(g3.admit(x_steps(2)));
  EXPECT_FALSE(g3.admit(x_steps(-1)));  // reversing by 3 steps a period at once
}

TEST(IncrementGuard, RefusesLeavingTheTravel) {
  const MachineConfig m = testing::test_machine();
  IncrementGuard g(m, at_x(1));
  ASSERT_TRUE(g.admit(x_steps(-1)));  // at 0: the end of travel
  EXPECT_FALSE(g.admit(x_steps(-2)));
  EXPECT_EQ(g.error().code, ErrorCode::RtSoftLimit);
}

TEST(IncrementGuard, AWrappingAxisHasNoTravelButItsLimits) {
  const MachineConfig m = testing::test_machine();  // C: 360 deg/s, 3600 deg/s², 0.001 deg
  IncrementGuard g(m, {});
  // C at 27 steps a period (360 deg/s) for turn after turn: no travel to leave
  PeriodIncrement inc;
  for (const std::int32_t d : {2, 4, 6, 8, 10, 12, 14, 16, 18, 20, 22, 24, 26, 27}) {
    inc.steps[5] = d;
    ASSERT_TRUE(g.admit(inc)) << d << " " << g.error().to_string();
  }
  inc.steps[5] = 27;
  for (int k = 0; k < 200'000; ++k) ASSERT_TRUE(g.admit(inc));
  EXPECT_GT(g.position(5), 360'000 * 10);
  inc.steps[5] = 29;  // 387 deg/s
  EXPECT_FALSE(g.admit(inc));
}

}  // namespace
}  // namespace lcnc

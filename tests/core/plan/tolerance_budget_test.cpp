#include "plan/tolerance_budget.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/plan/test_machine.h"
#include "plan/jerk_filter.h"
#include "plan/planner.h"
#include "plan/tolerances.h"

namespace lcnc {
namespace {

// m: half a step on each of X Y Z, as a distance; e_f as given.
TEST(ToleranceBudget, QuantizationIsHalfAStepPerLinearAxis) {
  const MachineConfig m = testing::test_machine();  // 1000 steps/mm on X Y Z
  const ToleranceBudget b = tolerance_budget(m, 0.0);
  EXPECT_NEAR(b.quantization_mm, std::sqrt(3.0) * 0.5e-3, 1e-15);
  EXPECT_EQ(b.jerk_filter_mm, 0.0);
  EXPECT_EQ(tolerance_budget(m, 0.002).jerk_filter_mm, 0.002);
}

// E = P − q − m − e_f, in that order.
TEST(ToleranceBudget, CornerGetsWhatTheOtherSharesLeave) {
  const ToleranceBudget b{0.001, 0.003};
  EXPECT_EQ(b.corner_mm(0.02, 0.005), ((0.02 - 0.005) - 0.001) - 0.003);
  EXPECT_EQ(b.corner_mm(0.01, 0.0), (0.01 - 0.001) - 0.003);
}

// The Planner computes the budget once, with the jerk filter's e_f, which
// stays within its share of the machine's path tolerance.
TEST(ToleranceBudget, PlannerTakesTheJerkFiltersDeviation) {
  MachineConfig m = testing::test_machine();
  m.max_jerk = 1e5;
  Planner p(m, [](Segment&) { return SourceStatus::End; });
  const JerkLimit lim = jerk_limit(m);
  ASSERT_TRUE(lim.enabled());
  EXPECT_EQ(p.tolerance_budget().jerk_filter_mm, lim.error_mm);
  EXPECT_EQ(p.tolerance_budget().quantization_mm, tolerance_budget(m, 0.0).quantization_mm);
  EXPECT_LE(lim.error_mm, jerk_filter_budget_mm(m));
  EXPECT_EQ(jerk_filter_budget_mm(m), plan::kJerkFilterShare * m.path_tolerance_mm);
}

}  // namespace
}  // namespace lcnc

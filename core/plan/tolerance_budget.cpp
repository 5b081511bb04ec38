#include "plan/tolerance_budget.h"

#include <cmath>

#include "plan/tolerances.h"

namespace lcnc {

double jerk_filter_budget_mm(const MachineConfig& machine) noexcept {
  return plan::kJerkFilterShare * machine.path_tolerance_mm;
}

ToleranceBudget tolerance_budget(const MachineConfig& machine, double jerk_filter_mm) noexcept {
  ToleranceBudget b;
  double sum = 0.0;
  for (int i = 0; i < 3; ++i) {
    const AxisConfig& ax = machine.axes[i];
    if (ax.present) sum += std::pow(0.5 / ax.steps_per_unit, 2);
  }
  b.quantization_mm = std::sqrt(sum);
  b.jerk_filter_mm = jerk_filter_mm;
  return b;
}

}  // namespace lcnc

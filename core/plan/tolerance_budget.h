// How a blended corner's tolerance is shared out (docs/design.md §5.1).
//
// A corner between two G64 blocks may leave the programmed path by at most
// P = min(P of the two blocks) (G64 P, or machine.path_tolerance_mm for a
// bare G64). The executed path carries more than the blend arc's own
// deviation, so the arc gets what is left:
//
//   E = P − q − m − e_f
//
//   q    the naive-CAM merger's share: max over the two blocks of
//        min(Q, P)/2 (G64 Q, plan/line_merger.h; 0 without Q). Per block.
//   m    the quantization margin: half a step on each linear axis, as a
//        distance, so that after rounding to steps the path stays within P.
//   e_f  the jerk filter's deviation (plan/jerk_filter.h; 0 without a jerk
//        limit), at most kJerkFilterShare · machine.path_tolerance_mm.
//
// m and e_f depend on the machine alone: computed once, where the Planner is
// built, and handed to the blender. Under tool-centre-point control the
// blender halves E again between X Y Z and the rotary axes (path_blender.cpp).
#pragma once

#include "machine/machine_config.h"

namespace lcnc {

struct ToleranceBudget {
  double quantization_mm = 0.0;  // m
  double jerk_filter_mm = 0.0;   // e_f

  // E for a corner whose P is p_mm and whose merger share is merge_mm (q),
  // in this order of subtraction (the plan is bit-identical to it).
  [[nodiscard]] double corner_mm(double p_mm, double merge_mm) const noexcept {
    return p_mm - merge_mm - quantization_mm - jerk_filter_mm;
  }
};

// The most e_f may take: kJerkFilterShare · machine.path_tolerance_mm (the
// rest stays for the blends of programs at the machine's P).
[[nodiscard]] double jerk_filter_budget_mm(const MachineConfig& machine) noexcept;

// m and e_f for a machine; jerk_filter_mm is JerkLimit::error_mm of the
// machine's jerk limit (0 when it has none).
[[nodiscard]] ToleranceBudget tolerance_budget(const MachineConfig& machine, double jerk_filter_mm) noexcept;

}  // namespace lcnc

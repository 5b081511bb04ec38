// The last check of the planner's output before the RT executes it: each
// period's increment against the axes' travel, velocity and acceleration.
// The planner plans within these limits; this guard holds them whatever the
// planner, the program or a segment built in code did, so no fault upstream
// ever reaches the motors as a jump.
//
// Per axis, with q the rounding of each period's target to whole steps:
//   travel        min ≤ position + d ≤ max            (not on a wrapping axis)
//   velocity      |d| ≤ ⌊vmax·T·spu⌋ + 1              one step of rounding
//   acceleration  |d − d_prev| ≤ ⌊amax·T²·spu⌋ + 2    a second difference of
//                                                     rounded targets: two steps
// with d the period's steps and d_prev the period before's (0 at the start:
// a job starts at rest). T is the nominal period: the RT scales the
// period by K ≤ 1 (rt/feed_override.h), which only slows the plan down.
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "common/error.h"
#include "machine/machine_config.h"
#include "plan/period_increment.h"

namespace lcnc {

class IncrementGuard {
 public:
  IncrementGuard(const MachineConfig& machine, const std::array<std::int64_t, kAxisCount>& start_steps);

  // Takes inc if it keeps every limit (the position advances); otherwise
  // returns false, takes nothing and says why in error() — code RtSoftLimit
  // or PlanBeyondLimit, the axis, what it would have done, inc's line.
  [[nodiscard]] bool admit(const PeriodIncrement& inc);
  [[nodiscard]] const Diagnostic& error() const noexcept { return error_; }
  [[nodiscard]] std::int64_t position(int axis) const noexcept { return at_[axis]; }

 private:
  void refuse(ErrorCode code, const PeriodIncrement& inc, const char* msg);

  const MachineConfig& machine_;
  std::array<std::int64_t, kAxisCount> at_{};  // position after the admitted entries, steps
  std::array<std::int64_t, kAxisCount> min_steps_{}, max_steps_{};
  std::array<std::int64_t, kAxisCount> max_inc_{}, max_inc_change_{};
  std::array<std::int64_t, kAxisCount> last_inc_{};
  Diagnostic error_;
};

}  // namespace lcnc

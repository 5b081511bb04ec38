// Leadscrew pitch-error compensation for one axis, in steps.
//
// The machine config gives a table (machine_config.h PitchTable, mm or deg):
// values[k] is added to the commanded position at start + k·interval, linear
// in between, end values held outside. Here the same table is scaled by
// steps_per_unit once, in the constructor, so that per period
//   correction_steps(c) = round(at(c))      with c, at(c) in steps,
// rounded to the nearest step (half away from zero). The RT kernel outputs
// c + correction_steps(c) per axis, so over a move from c0 to c1 the axis
// gets c1 − c0 + correction_steps(c1) − correction_steps(c0) pulses: the
// correction is a position offset, nothing accumulates.
//
// Per period the correction changes by at most
//   |correction_steps(c1) − correction_steps(c0)| ≤ max_slope()·|c1 − c0| + 1
// (the +1 is the rounding), the DDA headroom the caller reserves;
// machine_config.cpp's validate() checks it fits at max_velocity.
#pragma once

#include <cmath>
#include <cstdint>

#include "machine/machine_config.h"

namespace lcnc::rt {

class PitchCompensation {
 public:
  // Builds the step table from axis.pitch_compensation and
  // axis.steps_per_unit (allocates here, never in correction_steps()).
  // The config is assumed validated (interval > 0, ≥ 2 values or none).
  explicit PitchCompensation(const AxisConfig& axis);

  // Correction in steps at a commanded position in steps; 0 without a table.
  // RT path: noexcept, no allocation.
  [[nodiscard]] std::int64_t correction_steps(std::int64_t commanded_steps) const noexcept {
    if (table_steps_.empty()) return 0;
    return std::llround(table_steps_.at(static_cast<double>(commanded_steps)));
  }

  [[nodiscard]] bool empty() const noexcept { return table_steps_.empty(); }
  // Largest |Δcorrection / Δposition| of the table (dimensionless, the same
  // in mm and in steps); 0 without a table.
  [[nodiscard]] double max_slope() const noexcept { return max_slope_; }

 private:
  PitchTable table_steps_;  // positions and values in steps
  double max_slope_ = 0.0;
};

}  // namespace lcnc::rt

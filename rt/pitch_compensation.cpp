#include "rt/pitch_compensation.h"

namespace lcnc::rt {

PitchCompensation::PitchCompensation(const AxisConfig& axis)
    : table_steps_(axis.pitch_compensation.scaled(axis.steps_per_unit)),
      max_slope_(axis.pitch_compensation.max_slope()) {}

}  // namespace lcnc::rt

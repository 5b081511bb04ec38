// Where the DDA's pulses go (DESIGN §2): the simulated machine, the GHDL
// co-simulation, or a hardware driver. Called from the RT thread once per
// period, so implementations are noexcept and must not allocate, lock or block.
#pragma once

#include <array>
#include <cstdint>

#include "geom/pose.h"

namespace lcnc {

struct AxisPulses {
  std::uint32_t count = 0;               // pulses this period
  bool negative = false;                 // direction
  const std::uint32_t* ticks = nullptr;  // tick index (0 … N−1) of each pulse, increasing
};

struct PulseFrame {
  std::array<AxisPulses, kAxisCount> axes{};
  std::uint32_t ticks_per_period = 0;  // N, the DDA capacity
  float power_pct = 0.0f;              // laser output during the period
};

class PulseSink {
 public:
  virtual ~PulseSink() = default;
  virtual void emit(const PulseFrame& frame) noexcept = 0;
};

}  // namespace lcnc

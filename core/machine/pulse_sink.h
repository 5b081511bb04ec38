// Where the DDA's pulses go (docs/design.md §2): the simulated machine, the GHDL
// co-simulation, or a hardware driver — and where the machine's switch inputs
// come from. Called from the RT thread once per period, so implementations are
// noexcept and must not allocate, lock or block.
#pragma once

#include <array>
#include <cstdint>

#include "geom/pose.h"
#include "path/segment.h"

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
  // The program's outputs during the period (PeriodIncrement::outputs:
  // digital P0 … P7, then the assist gas bits; analog E0 … E3); all off
  // when no job is on the path.
  std::uint16_t outputs = 0;
  std::array<float, kAnalogOutputs> analog{};
};

// The machine's switch inputs as sampled once per period; true = active
// (tripped), whatever the wiring's polarity. Indexed by index(Axis).
struct MachineInputs {
  std::array<bool, kAxisCount> home{};       // home switch
  std::array<bool, kAxisCount> limit_min{};  // hard limit at the low end of travel
  std::array<bool, kAxisCount> limit_max{};  // hard limit at the high end of travel
  bool estop = false;                        // emergency stop pressed
  bool amp_fault = false;                    // a drive reports a fault
  int following_error_axis = -1;             // an axis past its following error, −1 if none
  std::uint8_t digital_in = 0;               // the program's inputs (M66 P0 … P7), bit n: P n
  // Feed inputs (M52, M53): a factor 0 … 1 on the feed where the program
  // turned adaptive feed on; a hold of the motion while true, unless the
  // program turned the input off.
  float adaptive_feed = 1.0f;
  bool feed_hold = false;
};

class PulseSink {
 public:
  virtual ~PulseSink() = default;
  virtual void send(const PulseFrame& frame) noexcept = 0;
  // The inputs now. Called from the RT thread once per period (noexcept, no
  // allocation, no lock). Default: a sink without inputs (nothing active).
  [[nodiscard]] virtual MachineInputs read_inputs() noexcept { return {}; }
};

}  // namespace lcnc

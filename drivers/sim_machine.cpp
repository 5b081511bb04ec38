#include "drivers/sim_machine.h"

namespace lcnc::drivers {

std::array<SimSwitches, kAxisCount> wired_switches(
    const MachineConfig& machine, const std::array<std::int64_t, kAxisCount>& raw_offset_steps) {
  std::array<SimSwitches, kAxisCount> out{};
  for (int i = 0; i < kAxisCount; ++i) {
    const AxisConfig& a = machine.axes[i];
    if (!a.present) continue;
    auto count = [&](double pos) {
      return std::llround(pos * a.steps_per_unit) + raw_offset_steps[i];
    };
    SimSwitches& s = out[i];
    // A wrapping axis turns without end: no hard limits to hit.
    if (!a.wrap) {
      s.limit_min_steps = count(a.min - kHardLimitBeyondSoft);
      s.limit_max_steps = count(a.max + kHardLimitBeyondSoft);
    }
    s.home = HomeSwitch{count(a.home_position_or_default()),
                        a.home_search_velocity_or_default() < 0.0 ? SwitchSide::Below
                                                                  : SwitchSide::Above};
  }
  return out;
}

SimMachine::SimMachine(const std::array<std::int64_t, kAxisCount>& start_steps)
    : SimMachine(start_steps, {}, {}) {}

SimMachine::SimMachine(const std::array<std::int64_t, kAxisCount>& start_steps,
                       const std::array<SimSwitches, kAxisCount>& switches,
                       const std::array<PitchTable, kAxisCount>& pitch_error_steps)
    : switches_(switches), pitch_error_steps_(pitch_error_steps) {
  for (int i = 0; i < kAxisCount; ++i) pos_[i].store(start_steps[i], std::memory_order_relaxed);
}

void SimMachine::emit(const PulseFrame& frame) noexcept {
  bool bad = false;
  for (int i = 0; i < kAxisCount; ++i) {
    const AxisPulses& ax = frame.axes[i];
    if (ax.count == 0) continue;
    // A drive sees one edge per tick at most, all inside the period.
    std::uint32_t prev = 0;
    for (std::uint32_t j = 0; j < ax.count; ++j) {
      const std::uint32_t t = ax.ticks[j];
      if (t >= frame.ticks_per_period || (j > 0 && t <= prev)) bad = true;
      prev = t;
    }
    const auto n = static_cast<std::int64_t>(ax.count);
    pos_[i].store(pos_[i].load(std::memory_order_relaxed) + (ax.negative ? -n : n),
                  std::memory_order_relaxed);
    pulses_[i].store(pulses_[i].load(std::memory_order_relaxed) + ax.count,
                     std::memory_order_relaxed);
  }
  if (bad) bad_frames_.fetch_add(1, std::memory_order_relaxed);
  frames_.fetch_add(1, std::memory_order_relaxed);
  if (frame.power_pct > 0.0f) laser_on_.fetch_add(1, std::memory_order_relaxed);
  power_.store(frame.power_pct, std::memory_order_relaxed);
}

MachineInputs SimMachine::read_inputs() noexcept {
  MachineInputs in;
  for (int i = 0; i < kAxisCount; ++i) {
    const SimSwitches& s = switches_[i];
    const std::int64_t pos = position_steps(i);
    if (s.home) {
      in.home[i] = s.home->active == SwitchSide::Below ? pos <= s.home->trip_steps
                                                       : pos >= s.home->trip_steps;
    }
    in.limit_min[i] = s.limit_min_steps && pos <= *s.limit_min_steps;
    in.limit_max[i] = s.limit_max_steps && pos >= *s.limit_max_steps;
  }
  in.estop = estop_.load(std::memory_order_relaxed);  // pairs with set_estop_input()
  return in;
}

}  // namespace lcnc::drivers

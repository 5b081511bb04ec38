#include "drivers/sim_machine.h"

#include <cstring>

namespace lcnc::drivers {

std::array<SimSwitches, kAxisCount> wired_switches(
    const MachineConfig& machine, const std::array<std::int64_t, kAxisCount>& raw_offset_steps) {
  std::array<SimSwitches, kAxisCount> out{};
  for (int i = 0; i < kAxisCount; ++i) {
    const AxisConfig& a = machine.axes[i];
    if (!a.present) continue;
    auto count = [&](double pos) { return std::llround(pos * a.steps_per_unit) + raw_offset_steps[i]; };
    SimSwitches& s = out[i];
    // A wrapping axis turns without end: no hard limits to hit.
    if (!a.wrap) {
      s.limit_min_steps = count(a.min - kHardLimitBeyondSoft);
      s.limit_max_steps = count(a.max + kHardLimitBeyondSoft);
    }
    s.home = HomeSwitch{count(a.home_position_or_default()),
                        a.home_search_velocity_or_default() < 0.0 ? SwitchSide::Below : SwitchSide::Above};
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

namespace {

// The ticks rise strictly and the last is inside the period (so all are):
// four neighbours compared at once, no branch.
bool ticks_rise_inside(const std::uint32_t* t, std::uint32_t count, std::uint32_t n_ticks) noexcept {
  using V4 = std::uint32_t __attribute__((vector_size(16)));
  V4 falls{};
  std::uint32_t j = 1;
  for (; j + 4 <= count; j += 4) {
    V4 cur, prev;
    std::memcpy(&cur, t + j, sizeof cur);
    std::memcpy(&prev, t + j - 1, sizeof prev);
    falls |= reinterpret_cast<V4>(cur <= prev);
  }
  std::uint32_t fall = falls[0] | falls[1] | falls[2] | falls[3];
  for (; j < count; ++j) fall |= t[j] <= t[j - 1] ? 1u : 0u;
  return fall == 0 && t[count - 1] < n_ticks;
}

}  // namespace

void SimMachine::send(const PulseFrame& frame) noexcept {
  bool bad = false;
  for (int i = 0; i < kAxisCount; ++i) {
    const AxisPulses& ax = frame.axes[i];
    if (ax.count == 0) continue;
    // A drive sees one edge per tick at most, all inside the period.
    if (!ticks_rise_inside(ax.ticks, ax.count, frame.ticks_per_period)) bad = true;
    const auto n = static_cast<std::int64_t>(ax.count);
    pos_[i].store(pos_[i].load(std::memory_order_relaxed) + (ax.negative ? -n : n),
                  std::memory_order_relaxed);
    pulses_[i].store(pulses_[i].load(std::memory_order_relaxed) + ax.count, std::memory_order_relaxed);
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
      in.home[i] =
          s.home->active == SwitchSide::Below ? pos <= s.home->trip_steps : pos >= s.home->trip_steps;
    }
    in.limit_min[i] = s.limit_min_steps && pos <= *s.limit_min_steps;
    in.limit_max[i] = s.limit_max_steps && pos >= *s.limit_max_steps;
  }
  in.estop = estop_.load(std::memory_order_relaxed);  // pairs with set_estop_input()
  in.digital_in = digital_in_.load(std::memory_order_relaxed);
  in.adaptive_feed = adaptive_feed_.load(std::memory_order_relaxed);
  in.feed_hold = feed_hold_.load(std::memory_order_relaxed);
  return in;
}

}  // namespace lcnc::drivers

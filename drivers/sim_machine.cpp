#include "drivers/sim_machine.h"

namespace lcnc::drivers {

SimMachine::SimMachine(const std::array<std::int64_t, kAxisCount>& start_steps) {
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

}  // namespace lcnc::drivers

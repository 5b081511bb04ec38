#include "rt/kernel_control.h"

#include <algorithm>
#include <cmath>

namespace lcnc::rt {

KernelControl::KernelControl(const MachineConfig& machine, KernelPort& port)
    : port_(port), ramp_(machine), period_s_(machine.period_s()) {
  for (const AxisConfig& ax : machine.axes)
    if (ax.present && ax.max_velocity > 0.0 && ax.max_acceleration > 0.0)
      brake_wait_s_ = std::max(brake_wait_s_, ax.max_velocity / ax.max_acceleration);
}

std::size_t KernelControl::braking_reserve(double k) const noexcept {
  // Entries consumed while K ramps linearly to 0 at ρ_max: ∫ K/T dt =
  // K²/(2ρT); before that, while the plan itself brakes at an axis's full
  // deceleration, K may have to wait (no room to fall): at most the longest
  // such braking, vmax/amax, at K.
  const double n = k * k / (2.0 * ramp_.rate_per_s() * period_s_) + k * brake_wait_s_ / period_s_;
  return static_cast<std::size_t>(std::ceil(n)) + 64;
}

RtFault KernelControl::fault() const noexcept {
  RtFault f;
  const std::uint16_t code = port_.fault_code.load(std::memory_order_acquire);
  f.active = code != 0;
  f.code = static_cast<ErrorCode>(code);
  f.axis = port_.fault_axis.load(std::memory_order_relaxed);
  f.line = port_.fault_line.load(std::memory_order_relaxed);
  return f;
}

}  // namespace lcnc::rt

#include "rt/feed_override.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace lcnc::rt {

FeedOverrideRamp::FeedOverrideRamp(const MachineConfig& machine) noexcept
    : k_max_(machine.max_feed_override) {
  // eq. (4): the axis with the least acceleration per unit of speed sets ρ.
  double accel_per_speed = std::numeric_limits<double>::infinity();  // 1/s
  for (const AxisConfig& ax : machine.axes) {
    if (ax.present && ax.max_velocity > 0.0)
      accel_per_speed = std::min(accel_per_speed, ax.max_acceleration / ax.max_velocity);
  }
  // No axis moves: any rate fits; one per second keeps K_min small.
  if (!std::isfinite(accel_per_speed)) accel_per_speed = 1.0;
  rate_per_s_ = kOverrideRampShare * accel_per_speed;
  k_min_ = std::sqrt(rate_per_s_ * machine.period_s());
}

double FeedOverrideRamp::clamp_target(double k) const noexcept {
  if (!(k > 0.0)) return 0.0;  // also NaN: the safe request is a hold
  return std::clamp(k, k_min_, k_max_);
}

double FeedOverrideRamp::period_scale(double e, double k_plan) const noexcept {
  if (!(e > 0.0)) return 0.0;
  const double k = k_plan > 1.0 ? e / k_plan : e;
  return std::clamp(k, k_min_, 1.0);
}

double FeedOverrideRamp::step(double k, double target, double length_s, const RampRoom& room) const noexcept {
  const double r0 = room.r0;
  if (k < target) {
    // the room at the K this step may reach (K² grows with it)
    const double k_next = std::min(target, k + rate_per_s_ * length_s);
    const double rate = std::clamp(r0 * (1.0 - k_next * k_next * room.up), 0.0, rate_per_s_);
    return std::min(target, k + rate * length_s);
  }
  const double rate = std::clamp(r0 * (1.0 - k * k * room.down), 0.0, rate_per_s_);
  const double dk = rate * length_s;
  double next = std::max(target, k - dk);
  // Stopping: the last moving period runs at exactly K_min (a smaller step
  // than dk), so the stop from there costs no more than the ramp (header).
  if (k > k_min_ && next < k_min_) next = k_min_;
  return next;
}

}  // namespace lcnc::rt
